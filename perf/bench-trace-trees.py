#!/usr/bin/env python3
"""DIRT's trace before and after a shader change, on one machine in one run:
runs BUILD's bench-trace once per glsl tree (DIRT_GLSL_DIR) in turn, ROUNDS
times, and keeps per scene, ray type and tree the best DIRT Mrays/s (the
least disturbed run). Prints one markdown table with each tree's figure and
its ratio to the first tree's. A tree is a directory laid out as glsl/, or
NAME=GITREV, which extracts that commit's glsl/ into a temporary directory;
either may end in @ARGS, more bench-trace arguments for that tree only
(comma-separated), e.g. none=glsl@--large,0.

    perf/bench-trace-trees.py [--rounds N] BUILD TREE... -- [bench-trace args]

e.g. perf/bench-trace-trees.py build before=HEAD~1 after=glsl -- \\
         room.gltf default -W 256 -H 128 -S 1 -B 16
"""
import argparse
import collections
import os
import subprocess
import sys
import tempfile

TYPES = ("primary", "visibility", "specular", "glossy", "diffuse")


def tree_dir(spec, tmp):
    spec, _, extra = spec.partition("@")
    extra = [x for x in extra.split(",") if x]
    name, _, where = spec.partition("=")
    if not where:
        name, where = spec, spec
    if os.path.isdir(where):
        return name, where, extra
    out = os.path.join(tmp, name)
    os.makedirs(out)
    archive = subprocess.run(["git", "archive", where, "glsl"], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", out], input=archive, check=True)
    return name, os.path.join(out, "glsl"), extra


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("build")
    ap.add_argument("rest", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    if "--" not in a.rest:
        ap.error("give the trees, then -- and bench-trace's arguments")
    cut = a.rest.index("--")
    specs, args = a.rest[:cut], a.rest[cut + 1:]
    if len(specs) < 2:
        ap.error("give at least two trees")
    best = collections.defaultdict(float)
    gpu = ""
    with tempfile.TemporaryDirectory() as tmp:
        trees = [tree_dir(s, tmp) for s in specs]
        for _ in range(a.rounds):
            for name, d, extra in trees:
                out = subprocess.run([a.build + "/perf/bench-trace"] + args + extra, check=True,
                                     capture_output=True, text=True,
                                     env=dict(os.environ, DIRT_GLSL_DIR=os.path.abspath(d))).stdout
                for line in out.splitlines():
                    if line.startswith("GPU:"):
                        gpu = line[4:].strip()
                    c = [x.strip() for x in line.strip().strip("|").split("|")]
                    if len(c) == 8 and c[4] in TYPES:
                        k = (c[0], c[4], name)
                        best[k] = max(best[k], float(c[5]))
    names = [n for n, _, _ in trees]
    print("GPU: %s\n" % gpu)
    print("best DIRT Mrays/s of %d rounds (bench-trace %s)\n" % (a.rounds, " ".join(args)))
    print("| scene | type | " + " | ".join(names) + " | " +
          " | ".join("%s / %s" % (n, names[0]) for n in names[1:]) + " |")
    print("|---|---|" + "---|" * (2 * len(names) - 1))
    scenes = []
    for s, _, _ in best:
        if s not in scenes:
            scenes.append(s)
    for s in scenes:
        for t in TYPES:
            v = [best[(s, t, n)] for n in names]
            if not v[0]:
                continue
            print("| %s | %s | " % (s, t) + " | ".join("%.3f" % x for x in v) + " | " +
                  " | ".join("%.2f" % (x / v[0]) for x in v[1:]) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
