#!/usr/bin/env python3
"""The path tracer before and after a change, on one machine in one run:
renders each scene with each engine through BEFORE_BUILD's and
AFTER_BUILD's dirt-render in turn (--stats), ROUNDS times, and keeps per
scene, engine and tree the least trace, fetch + shade and whole
path-tracing time (trace + fetch + shade + direct visibility; the build is
not part of it). Prints one markdown table with the paths per event of the
after tree.

    perf/bench-pt-trees.py [--rounds N] [--engines dirt,mmrt] BEFORE_BUILD AFTER_BUILD \\
        -- SCENE... [-- dirt-render args]

e.g. perf/bench-pt-trees.py ../before/build build -- default room.gltf \\
         -- -W 256 -H 128 --spp 2 --background 0.5,0.5,0.5
"""
import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--engines", default="dirt,mmrt")
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("rest", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    rest = a.rest[1:] if a.rest and a.rest[0] == "--" else a.rest
    if "--" in rest:
        cut = rest.index("--")
        scenes, args = rest[:cut], rest[cut + 1:]
    else:
        scenes, args = rest, []
    if not scenes:
        ap.error("give the scenes after --")
    trees = {"before": a.before, "after": a.after}
    engines = a.engines.split(",")
    best = collections.defaultdict(lambda: float("inf"))
    paths = {}
    with tempfile.TemporaryDirectory() as tmp:
        out, stats = os.path.join(tmp, "img.exr"), os.path.join(tmp, "stats.json")
        for _ in range(a.rounds):
            for sc in scenes:
                for e in engines:
                    for t, b in trees.items():
                        cmd = [b + "/src/app/dirt-render"] + ([] if sc == "default" else [sc])
                        cmd += ["--engine", e, "-o", out, "--stats", stats, "-q"] + args
                        subprocess.run(cmd, check=True, capture_output=True)
                        d = json.load(open(stats))
                        k = (sc, e, t)
                        pt = d["trace_ms"] + d["fetch_ms"] + d["shade_ms"] + d["visibility_ms"]
                        best[k + ("trace",)] = min(best[k + ("trace",)], d["trace_ms"])
                        best[k + ("fs",)] = min(best[k + ("fs",)], d["fetch_ms"] + d["shade_ms"])
                        best[k + ("pt",)] = min(best[k + ("pt",)], pt)
                        if t == "after":
                            paths[(sc, e)] = d.get("paths_per_event", [])
    print("least of %d rounds; dirt-render %s\n" % (a.rounds, " ".join(args)))
    print("| scene | engine | paths per event (after) | trace ms before | after | "
          "fetch + shade ms before | after | path tracing ms before | after | after / before |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for sc in scenes:
        for e in engines:
            def g(t, f):
                return best[(sc, e, t, f)]
            print("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f |" % (
                os.path.basename(sc), e, " ".join(str(n) for n in paths[(sc, e)]),
                g("before", "trace"), g("after", "trace"), g("before", "fs"), g("after", "fs"),
                g("before", "pt"), g("after", "pt"), g("after", "pt") / g("before", "pt")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
