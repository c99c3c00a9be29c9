#!/usr/bin/env python3
"""Where the DIRT build's time goes, by swapping shader variants: copies
glsl/ into a temporary directory once per variant, applies that variant's
one edit to the build shaders, and runs bench-ads (DIRT_GLSL_DIR) for every
variant in turn, ROUNDS times; prints per variant the least depth-pass and
total build time. The variants (all but "as built" and "reference clip"
give wrong structures; they only take work away):

  as built        the build as it is
  reference clip  the plain Sutherland-Hodgman clip of every candidate
                  (bench-ads --reference-clip)
  no range        the range replaced by the triangle's vertex depths
  no atomics      the range computed, but no depth atomics and no append
  no fragment     the fragment shader returns after the tile check
  1-pixel quads   the geometry shader's quads cut to one tile, fragment
                  shader as in "no fragment"
  culled quads    zero-area quads (culled by triangle setup)
  no quads        the geometry shader emits nothing
  no near/far     the geometry shader skips the near/far clip

    perf/build-variants.py [--rounds N] BUILD -- [bench-ads args]
e.g. perf/build-variants.py --rounds 3 build -- room.gltf -W 256 -H 256 -S 1 -B 4
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FRAG_RANGE = ("    if (!dirt_range_tile(v, S, tile, g_p0, g_p1, g_p2, g_p3, g_p4, g_n, "
              "float(DIRT_CLIP_EPS),")
VARIANTS = [
    ("as built", None, []),
    ("reference clip", None, ["--reference-clip"]),
    ("no range", [("dirt/clip.glsl", "    vec4 R = dirt_tile_rect(v, S, t, eps);\n",
                   "    vec4 R = dirt_tile_rect(v, S, t, eps);\n    zmin = min(p0.w, min(p1.w, "
                   "p2.w));\n    zmax = max(p0.w, max(p1.w, p2.w));\n    return true;\n")], []),
    ("no atomics", [("dirt/build.frag", "    atomicMin(depth[t].x, floatBitsToUint(zmin));",
                     "    if (zmin > -1e30)\n        return;\n"
                     "    atomicMin(depth[t].x, floatBitsToUint(zmin));")], []),
    ("no fragment", [("dirt/build.frag", "#elif defined(DIRT_PASS_DEPTH)\n",
                      "#elif defined(DIRT_PASS_DEPTH)\n    if (g_n > -5)\n        return;\n")], []),
    ("1-pixel quads", [("dirt/build.frag", "#elif defined(DIRT_PASS_DEPTH)\n",
                        "#elif defined(DIRT_PASS_DEPTH)\n    if (g_n > -5)\n        return;\n"),
                       ("dirt/build.geom", "    emit(base + vec2(lo.x, lo.y), poly, poly_n, prim, view);",
                        "    hi = min(hi, lo + 0.9);\n"
                        "    emit(base + vec2(lo.x, lo.y), poly, poly_n, prim, view);")], []),
    ("culled quads", [("dirt/build.frag", "#elif defined(DIRT_PASS_DEPTH)\n",
                       "#elif defined(DIRT_PASS_DEPTH)\n    if (g_n > -5)\n        return;\n"),
                      ("dirt/build.geom", "    emit(base + vec2(lo.x, lo.y), poly, poly_n, prim, view);",
                       "    hi = lo;\n    emit(base + vec2(lo.x, lo.y), poly, poly_n, prim, view);")], []),
    ("no quads", [("dirt/build.geom", "    vec2 base = vec2(float(v.placement.y), 0.0);\n",
                   "    vec2 base = vec2(float(v.placement.y), 0.0);\n    if (poly_n > -5)\n"
                   "        return;\n")], []),
    ("no near/far", [("dirt/build.geom",
                      "    dirt_clip_near_far(c, float(DIRT_CLIP_EPS), poly, poly_n);",
                      "    poly = vec4[5](c[0], c[1], c[2], c[2], c[2]);\n    poly_n = 3;")], []),
]


def make(tmp, name, edits):
    d = os.path.join(tmp, name.replace(" ", "_").replace("/", "_"))
    shutil.copytree(os.path.join(ROOT, "glsl"), d)
    for path, old, new in edits or []:
        p = os.path.join(d, path)
        s = open(p).read()
        if old not in s:
            sys.exit(f"build-variants: {name}: {path} lacks the line it edits")
        open(p, "w").write(s.replace(old, new, 1))
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("build")
    ap.add_argument("args", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    args = a.args[1:] if a.args[:1] == ["--"] else a.args
    best = {}
    with tempfile.TemporaryDirectory() as tmp:
        dirs = [(n, make(tmp, n, e), extra) for n, e, extra in VARIANTS]
        for r in range(a.rounds):
            for name, d, extra in dirs:
                env = dict(os.environ, DIRT_GLSL_DIR=d)
                out = subprocess.run([a.build + "/perf/bench-ads"] + args + ["--repeat", "3",
                                     "--min"] + extra, env=env, check=True,
                                     capture_output=True, text=True).stdout
                head = next(l for l in out.splitlines() if l.startswith("| scene"))
                cols = [c.strip() for c in head.strip().strip("|").split("|")]
                for line in out.splitlines():
                    if not line.startswith("| ") or line.startswith("| scene"):
                        continue
                    c = [x.strip() for x in line.strip().strip("|").split("|")]
                    row = dict(zip(cols, c))
                    key = (row["scene"], row["S"], name)
                    depth, total = float(row["depth bounds ms"]), float(row["total ms"])
                    old = best.get(key)
                    best[key] = (min(depth, old[0]) if old else depth,
                                 min(total, old[1]) if old else total, row["n_p"])
            print(f"round {r + 1}/{a.rounds} done", file=sys.stderr)
    print("| scene | S | variant | n_p | depth pass ms | build ms |\n|---|---|---|---|---|---|")
    for (scene, s, name), (depth, total, np_) in best.items():
        print(f"| {scene} | {s} | {name} | {np_} | {depth:.1f} | {total:.1f} |")


if __name__ == "__main__":
    main()
