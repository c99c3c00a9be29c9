#!/usr/bin/env bash
# The large primitives' grid (--large-grid; doc/dirt-trace.md, "The large
# primitives' grid"): DIRT with and without it on the default scene, the
# generated scenes (perf/gen-scenes.sh: a closed room with dense geometry,
# objects over a mirror floor, thin slats at grazing angles) and any SCENE
# given.
#  - Work (--count-work, one run per mode: counts, hardware-neutral, fine
#    on a loaded machine): per ray type the DIRT triangle tests and Hi-Z
#    steps per ray without / with the grid and the triangle tests over
#    Embree's (its BVH walk over the same rays).
#  - Time (REPEATS > 0; a quiet machine only): dirt-render without and with
#    the grid interleaved (off, on, off, ...), REPEATS times each; per scene
#    the minimum over the repeats of the frame (build + SPP samples,
#    total_ms), of the traces (trace_ms) and of the build (build_ms, which
#    includes the grid's CPU clip), and on / off. The images must be equal
#    bit for bit (checked: exit 1 if not).
# Record the figures with their command, machine and driver in
# perf/results/ (counts: work-llvmpipe.md).
#
#   perf/bench-large-grid.sh [BUILD_DIR] [WxH] [SPP] [REPEATS] [SCENE...]
#   (REPEATS 0: the counts only; defaults build 256x192 4 5)
set -euo pipefail
build=${1:-build}
res=${2:-256x192}
spp=${3:-4}
reps=${4:-5}
shift $(( $# > 4 ? 4 : $# ))
render=$build/src/app/dirt-render
cmp=$build/test/e2e/exr_compare
tmp=$(mktemp -d /tmp/dirt-bench-large-grid-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
"$(dirname "$0")/gen-scenes.sh" "$tmp" >/dev/null
scenes=(default "$tmp"/room69k.gltf "$tmp"/mirror69k.glb "$tmp"/slats69k.glb "$@")
W=${res%x*} H=${res#*x}
status=0

echo "Work per ray at $W x $H (the hit-agreement rays of each type, seed 0), DIRT without / with the grid"
echo
echo "| scene | ray type | tri tests off | on | on / off | Hi-Z steps off | on | Embree tri tests | DIRT / Embree off | on |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for mode in off on; do
    flag=(); [ $mode = on ] && flag=(--large-grid)
    "$render" "$s" --engine dirt -W "$W" -H "$H" --spp 1 --count-work "${flag[@]}" \
      -o "$tmp/w$mode.png" --stats "$tmp/w$mode.json" -q
  done
  python3 - "$tmp" "$(basename "$s")" <<'PY'
import json, sys
tmp, name = sys.argv[1], sys.argv[2]
off, on = (json.load(open(f"{tmp}/w{m}.json"))["frames"][0]["work"] for m in ("off", "on"))
for t, a in off.items():
    b, n = on[t], a["rays"]
    e = a["embree"]["triangle_tests"]
    print(f"| {name} | {t} | {a['triangle_tests'] / n:.2f} | {b['triangle_tests'] / n:.2f} | "
          f"{b['triangle_tests'] / max(a['triangle_tests'], 1):.3f} | {a['hiz_steps'] / n:.2f} | "
          f"{b['hiz_steps'] / n:.2f} | {e / n:.2f} | {a['triangle_tests'] / e:.2f} | "
          f"{b['triangle_tests'] / e:.2f} |")
PY
done
[ "$reps" -gt 0 ] || exit 0

echo
echo "Time at $W x $H, $spp spp, 4 bounces; minimum of $reps interleaved runs each"
echo
echo "| scene | frame ms off | on | on / off | traces ms off | on | on / off | build ms off | on |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for r in $(seq "$reps"); do
    for mode in off on; do
      flag=(); [ $mode = on ] && flag=(--large-grid)
      "$render" "$s" --engine dirt -W "$W" -H "$H" --spp "$spp" "${flag[@]}" \
        -o "$tmp/$mode.exr" --stats "$tmp/$mode$r.json" -q
    done
    "$cmp" --exact "$tmp/off.exr" "$tmp/on.exr" >/dev/null ||
      { echo "$s: the image with the grid differs" >&2; status=1; }
  done
  python3 - "$tmp" "$reps" "$(basename "$s")" <<'PY'
import json, sys
tmp, reps, name = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def best(mode):
    f = [json.load(open(f"{tmp}/{mode}{r}.json"))["frames"][0] for r in range(1, reps + 1)]
    return [min(x[k] for x in f) for k in ("total_ms", "trace_ms", "build_ms")]
a, b = best("off"), best("on")
print(f"| {name} | {a[0]:.1f} | {b[0]:.1f} | {b[0] / a[0]:.3f} | {a[1]:.1f} | {b[1]:.1f} | "
      f"{b[1] / a[1]:.3f} | {a[2]:.1f} | {b[2]:.1f} |")
PY
done
exit $status
