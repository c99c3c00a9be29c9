#!/usr/bin/env bash
# Timing of the ray sort (--sort-rays; doc/light-transport-gpu.md, "Ray
# sort"): dirt-render with and without it, interleaved (unsorted, sorted,
# unsorted, ...), REPEATS times each, on the default scene, the generated
# scenes (perf/gen-scenes.sh) and any SCENE given, for the DIRT and MMRT
# engines. Prints per scene and engine the minimum over the repeats of the
# frame (build + every pass of SPP samples, total_ms), of the traces
# (trace_ms: closest-hit and shadow traces) and of the sort's passes
# (the "ray sort" pass), and sorted / unsorted. Times: run it on a quiet
# machine; record the figures with the machine and driver in
# perf/results/. The images must be equal bit for bit (checked: exit 1 if
# not).
#
#   perf/bench-sort.sh [BUILD_DIR] [WxH] [SPP] [REPEATS] [SCENE...]
set -euo pipefail
build=${1:-build}
res=${2:-256x192}
spp=${3:-4}
reps=${4:-5}
shift $(( $# > 4 ? 4 : $# ))
render=$build/src/app/dirt-render
cmp=$build/test/e2e/exr_compare
tmp=$(mktemp -d /tmp/dirt-bench-sort-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
"$(dirname "$0")/gen-scenes.sh" "$tmp" >/dev/null
scenes=(default "$tmp"/room69k.gltf "$tmp"/mirror69k.glb "$tmp"/slats69k.glb "$@")
W=${res%x*} H=${res#*x}
echo "$W x $H, $spp spp, 4 bounces; minimum of $reps interleaved runs each"
echo
echo "| scene | engine | frame ms unsorted | sorted | sorted / unsorted | traces ms unsorted | sorted | sort passes ms | (traces + sort) / traces |"
echo "|---|---|---|---|---|---|---|---|---|"
status=0
for s in "${scenes[@]}"; do
  for e in dirt mmrt; do
    for r in $(seq "$reps"); do
      for mode in u s; do
        flag=(); [ $mode = s ] && flag=(--sort-rays)
        "$render" "$s" --engine $e -W "$W" -H "$H" --spp "$spp" "${flag[@]}" \
          -o "$tmp/$mode.exr" --stats "$tmp/$mode$r.json" -q
      done
      "$cmp" --exact "$tmp/u.exr" "$tmp/s.exr" >/dev/null ||
        { echo "$s $e: the sorted image differs" >&2; status=1; }
    done
    python3 - "$tmp" "$reps" "$(basename "$s")" $e <<'PY'
import json, sys
tmp, reps, name, eng = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
def runs(mode):
    out = []
    for r in range(1, reps + 1):
        f = json.load(open(f"{tmp}/{mode}{r}.json"))["frames"][0]
        sort = sum(p["ms"] for p in f["passes"] if p["name"] == "ray sort")
        out.append((f["total_ms"], f["trace_ms"], sort))
    return out
u, s = runs("u"), runs("s")
fu, fs = min(x[0] for x in u), min(x[0] for x in s)
tu, ts = min(x[1] for x in u), min(x[1] for x in s)
ss = min(x[2] for x in s)
print(f"| {name} | {eng} | {fu:.1f} | {fs:.1f} | {fs / fu:.3f} | {tu:.1f} | {ts:.1f} | "
      f"{ss:.1f} | {(ts + ss) / tu:.3f} |")
PY
  done
done
exit $status
