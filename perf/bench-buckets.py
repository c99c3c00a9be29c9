#!/usr/bin/python3
"""Uniform against adaptive depth buckets (dirt-render --depth-buckets;
doc/dirt-build.md, "Adaptive depth buckets") at the same B, per scene.

  perf/bench-buckets.py counts [--build-dir build] [-W 128] [-H 96] [-B 8 16] [SCENE...]
  perf/bench-buckets.py times  [--build-dir build] [-W 256] [-H 256] [-B 8] [--rounds 5]
                               [--spp 4] [SCENE...]

counts: one render per (scene, B, mode) with --count-work; per ray type the
work per ray (tiles walked, Hi-Z steps, list nodes read, exact triangle
tests, Embree's triangle tests), and the structure's memory (id nodes, c,
heads, edges, histogram, total). Deterministic (shadow rays within a few
hundredths), so any machine may record them.
times: --rounds rounds, each rendering every (scene, B) once per mode,
uniform and adaptive interleaved (so drift hits both alike); the medians of
the build, trace and whole-frame times and the ratios adaptive / uniform.
Run it on a quiet machine.

Without SCENE: the default scene, the Cornell box and FlightHelmet from
../shared/scenes (when present) and perf/gen-scenes.sh's room69k,
mirror69k and slats69k (generated into a temporary directory)."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MODES = ("uniform", "adaptive")


def scenes_default(tmp):
    out = ["default"]
    shared = os.path.join(HERE, "..", "..", "shared", "scenes")
    for rel in ("cornell/CornellBox-Original.obj", "gltf/FlightHelmet/FlightHelmet.gltf"):
        p = os.path.normpath(os.path.join(shared, rel))
        if os.path.exists(p):
            out.append(p)
    subprocess.run([os.path.join(HERE, "gen-scenes.sh"), tmp], check=True,
                   stdout=subprocess.DEVNULL)
    out += [os.path.join(tmp, n) for n in ("room69k.gltf", "mirror69k.glb", "slats69k.glb")]
    return out


def render(a, tmp, scene, B, mode, extra):
    stats = os.path.join(tmp, "stats.json")
    cmd = [os.path.join(a.build_dir, "src", "app", "dirt-render"), scene, "--engine", "dirt",
           "-W", str(a.W), "-H", str(a.H), "-B", str(B), "--depth-buckets", mode,
           "-o", os.path.join(tmp, "out.png"), "--stats", stats, "-q"] + extra
    subprocess.run(cmd, check=True)
    with open(stats) as f:
        return json.load(f)


def name(scene):
    return os.path.basename(scene)


def counts(a, tmp):
    print("Work per ray and memory, uniform (u) and adaptive (a) depth buckets, %dx%d, 1 spp, "
          "S auto, large primitives on (the defaults)\n" % (a.W, a.H))
    print("| scene | B | ray type | tiles u / a | Hi-Z steps u / a | list nodes u / a | "
          "tri tests u / a | Embree tri tests |")
    print("|---|---|---|---|---|---|---|---|")
    mem = []
    for s in a.scenes:
        for B in a.B:
            r = {m: render(a, tmp, s, B, m, ["--spp", "1", "--count-work"]) for m in MODES}
            wu, wa = (r[m]["frames"][0]["work"] for m in MODES)
            for t in wu:
                nu, na = wu[t]["rays"], wa[t]["rays"]
                f = lambda k: "%.2f / %.2f" % (wu[t][k] / nu, wa[t][k] / na)
                print("| %s | %d | %s | %s | %s | %s | %s | %.2f |" % (
                    name(s), B, t, f("tiles"), f("hiz_steps"), f("list_nodes"),
                    f("triangle_tests"), wu[t]["embree"]["triangle_tests"] / nu))
            mem.append((s, B, r))
    print("\nMemory (bytes_total = used bytes of the structure, stats JSON; MB)\n")
    print("| scene | B | c u / a | id nodes u / a | heads | edges (a) | histogram (a) | "
          "total u / a | a / u |")
    print("|---|---|---|---|---|---|---|---|---|")
    for s, B, r in mem:
        u, ad = r["uniform"], r["adaptive"]
        bu, ba = u["bytes"], ad["bytes"]
        print("| %s | %d | %.2f / %.2f | %.2f / %.2f | %.2f | %.2f | %.2f | %.2f / %.2f | %.2f |" % (
            name(s), B, u["buckets_per_sample"], ad["buckets_per_sample"],
            bu["id nodes"] / 1e6, ba["id nodes"] / 1e6, bu["list heads"] / 1e6,
            ba.get("bucket edges", 0) / 1e6, ba.get("bucket histogram", 0) / 1e6,
            u["bytes_total"] / 1e6, ad["bytes_total"] / 1e6, ad["bytes_total"] / u["bytes_total"]))


def times(a, tmp):
    got = {}
    for rnd in range(a.rounds):
        for s in a.scenes:
            for B in a.B:
                for m in (MODES if rnd % 2 == 0 else MODES[::-1]):
                    r = render(a, tmp, s, B, m, ["--spp", str(a.spp)])
                    got.setdefault((s, B, m), []).append(r)
        print("round %d of %d done" % (rnd + 1, a.rounds), file=sys.stderr)
    print("Times, uniform (u) and adaptive (a) depth buckets, %dx%d, %d spp, medians of %d "
          "interleaved rounds (ms)\n" % (a.W, a.H, a.spp, a.rounds))
    print("| scene | B | build u / a | trace u / a | frame u / a | build a/u | trace a/u | "
          "frame a/u |")
    print("|---|---|---|---|---|---|---|---|")
    for s in a.scenes:
        for B in a.B:
            med = {m: {k: statistics.median(x[k] for x in got[(s, B, m)])
                       for k in ("build_ms", "trace_ms", "total_ms")} for m in MODES}
            u, ad = med["uniform"], med["adaptive"]
            print("| %s | %d | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.2f | %.2f | %.2f |" % (
                name(s), B, u["build_ms"], ad["build_ms"], u["trace_ms"], ad["trace_ms"],
                u["total_ms"], ad["total_ms"], ad["build_ms"] / u["build_ms"],
                ad["trace_ms"] / u["trace_ms"], ad["total_ms"] / u["total_ms"]))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("what", choices=("counts", "times"))
    p.add_argument("scenes", nargs="*")
    p.add_argument("--build-dir", default="build")
    p.add_argument("-W", type=int)
    p.add_argument("-H", type=int)
    p.add_argument("-B", type=int, nargs="+")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--spp", type=int, default=4)
    a = p.parse_args()
    big = a.what == "times"
    a.W = a.W or (256 if big else 128)
    a.H = a.H or (256 if big else 96)
    a.B = a.B or ([8] if big else [8, 16])
    with tempfile.TemporaryDirectory(prefix="dirt-bench-buckets-") as tmp:
        a.scenes = a.scenes or scenes_default(tmp)
        (counts if a.what == "counts" else times)(a, tmp)


if __name__ == "__main__":
    main()
