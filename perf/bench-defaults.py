#!/usr/bin/env python3
"""Chooses DIRT's defaults by measurement (issue 16, item 6): the whole
frame (build + one path-traced sample: trace, fetch, shade and the rest of
the path tracer's passes) of dirt-render for every tile size S, bucket
count B and build (raster, compute) on each scene, at dirt-render's default
structure (camera view + six cube faces), in rounds that run every
configuration once in turn (interleaved, so load changes hit all alike);
the figure per configuration is the minimum over the rounds. Prints a
markdown table per scene and the geometric mean over the scenes of each
configuration's time relative to the scene's best, and writes the raw
figures as JSON.

    perf/bench-defaults.py [--render build/src/app/dirt-render] [--rounds 3]
        [--size 320x240] [--tiles 1,2,4] [--buckets 8,16,32]
        [--builds raster,compute] [--json OUT.json] SCENE...

SCENE: a glTF/OBJ path or "default" (the embedded scene). Every number is
dirt-render's own --stats figures (the CPU clock on llvmpipe), never a
process's wall time (context creation and scene loading are left out).
"""
import argparse
import itertools
import json
import math
import os
import subprocess
import sys
import tempfile


def frame_ms(render, scene, size, s, b, build):
    w, h = size.split("x")
    with tempfile.TemporaryDirectory() as d:
        out, stats = os.path.join(d, "f.exr"), os.path.join(d, "s.json")
        cmd = [render] + ([] if scene == "default" else [scene]) + [
            "-o", out, "-W", w, "-H", h, "--spp", "1", "-S", str(s), "-B", str(b),
            "--build", build, "--stats", stats, "-q"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()[-300:]))
        with open(stats) as f:
            st = json.load(f)
    passes = sum(p["ms"] for p in st["passes"])
    return {"build": st["build_ms"], "frame": passes, "mb": st["bytes_total"] / 1e6,
            "clock": sorted(set(p["clock"] for p in st["passes"]))}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--render", default="build/src/app/dirt-render")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--size", default="320x240")
    ap.add_argument("--tiles", default="1,2,4")
    ap.add_argument("--buckets", default="8,16,32")
    ap.add_argument("--builds", default="raster,compute")
    ap.add_argument("--json")
    a = ap.parse_args()
    configs = list(itertools.product([int(x) for x in a.tiles.split(",")],
                                     [int(x) for x in a.buckets.split(",")],
                                     a.builds.split(",")))
    best = {}
    for rnd in range(a.rounds):
        for scene in a.scenes:
            for c in configs:
                m = frame_ms(a.render, scene, a.size, *c)
                k = (scene,) + c
                if k not in best or m["frame"] < best[k]["frame"]:
                    best[k] = m
            print("round %d/%d: %s done" % (rnd + 1, a.rounds, scene), file=sys.stderr)
    rel = {c: [] for c in configs}
    for scene in a.scenes:
        low = min(best[(scene,) + c]["frame"] for c in configs)
        print("\n**%s** (%s, spp 1, minimum of %d interleaved rounds; clock: %s)\n" %
              (scene, a.size, a.rounds, ",".join(best[(scene,) + configs[0]]["clock"])))
        print("| S | B | build | build ms | frame ms | frame / best | MB |")
        print("|---|---|---|---|---|---|---|")
        for c in configs:
            m = best[(scene,) + c]
            rel[c].append(m["frame"] / low)
            print("| %d | %d | %s | %.1f | %.1f | %.2f | %.1f |" %
                  (c[0], c[1], c[2], m["build"], m["frame"], m["frame"] / low, m["mb"]))
    print("\n**Geometric mean over the scenes of frame / the scene's best**\n")
    print("| S | B | build | geomean |")
    print("|---|---|---|---|")
    for c in sorted(configs, key=lambda c: math.prod(rel[c]) ** (1 / len(rel[c]))):
        g = math.prod(rel[c]) ** (1 / len(rel[c]))
        print("| %d | %d | %s | %.3f |" % (c[0], c[1], c[2], g))
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"scene": k[0], "S": k[1], "B": k[2], "mode": k[3], "build_ms": v["build"],
                        "frame_ms": v["frame"], "mb": v["mb"], "clock": v["clock"]}
                       for k, v in best.items()], f, indent=1)


if __name__ == "__main__":
    main()
