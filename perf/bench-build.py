#!/usr/bin/env python3
"""DIRT's build before and after a change, against MMRT's, on one machine in
one run: runs the bench-build program of each build directory in turn,
ROUNDS times (each run builds every structure once, then --repeat rounds in
turn, and reports each one's minimum), and keeps per scene and technique the
minimum over all runs. MMRT's time is the minimum over both trees' runs (its
code is the same). Prints one markdown table.

    perf/bench-build.py [--rounds N] BEFORE_BUILD AFTER_BUILD -- [bench-build args]

e.g. perf/bench-build.py --rounds 3 ../before/build build -- default room.gltf \\
         -W 256 -H 256 -S 1,2 -B 4 --repeat 3
"""
import argparse
import subprocess
import sys


def run(build, args):
    out = subprocess.run([build + "/perf/bench-build"] + args, check=True,
                         capture_output=True, text=True).stdout
    rows, gpu = [], ""
    for line in out.splitlines():
        if line.startswith("GPU:"):
            gpu = line[4:].strip()
        if not line.startswith("| ") or line.startswith("| scene"):
            continue
        c = [x.strip() for x in line.strip().strip("|").split("|")]
        rows.append({"scene": c[0], "tris": c[1], "tech": c[2], "records": c[3], "mb": c[4],
                     "first": float(c[5]), "runs": c[6], "ms": float(c[7]), "passes": c[8]})
    return rows, gpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("args", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    args = a.args[1:] if a.args[:1] == ["--"] else a.args
    best = {}  # (tree, scene, tech) -> row with the least ms
    gpu = ""
    for r in range(a.rounds):
        for tree, build in (("before", a.before), ("after", a.after)):
            rows, gpu = run(build, args)
            for row in rows:
                key = (tree, row["scene"], row["tech"])
                old = best.get(key)
                if old is None or row["ms"] < old["ms"]:
                    first = min(row["first"], old["first"]) if old else row["first"]
                    best[key] = dict(row, first=first)
                else:
                    old["first"] = min(old["first"], row["first"])
            print(f"round {r + 1}/{a.rounds} {tree} done", file=sys.stderr)
    print(f"GPU: {gpu}\n")
    print("| scene | tris | S | MMRT fragments | MMRT ms | DIRT n_p before / after | "
          "DIRT ms before | DIRT ms after | before / MMRT | after / MMRT | speed-up | "
          "first build ms before (runs) | first build ms after (runs) | after: passes of the "
          "least round |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    scenes = []
    for (tree, scene, tech) in best:
        if scene not in scenes:
            scenes.append(scene)
    for scene in scenes:
        mm = [best[k] for k in best if k[1] == scene and k[2] == "MMRT"]
        m = min(mm, key=lambda x: x["ms"])
        techs = sorted({k[2] for k in best if k[1] == scene and k[2].startswith("DIRT")})
        for tech in techs:
            b, f = best.get(("before", scene, tech)), best.get(("after", scene, tech))
            if not b or not f:
                continue
            s = tech.split("S=")[1]
            print(f"| {scene} | {f['tris']} | {s} | {m['records']} | {m['ms']:.1f} | "
                  f"{b['records']} / {f['records']} | {b['ms']:.1f} | {f['ms']:.1f} | "
                  f"{b['ms'] / m['ms']:.2f} | {f['ms'] / m['ms']:.2f} | "
                  f"{b['ms'] / f['ms']:.1f}x | {b['first']:.1f} ({b['runs']}) | "
                  f"{f['first']:.1f} ({f['runs']}) | {f['passes']} |")
    print(f"\nMMRT: its passes of the least round: " + "; ".join(
        f"{sc}: {min([best[k] for k in best if k[1] == sc and k[2] == 'MMRT'], key=lambda x: x['ms'])['passes']}"
        for sc in scenes))


if __name__ == "__main__":
    main()
