#!/usr/bin/env bash
# DIRT's trace options that are bets on a GPU (each off by default, each the
# same image bit for bit): --bucket-masks (doc/dirt-build.md, "Pass 3"),
# --sub-tiles ("Sub-tile rectangles"), --node-depths ("Node depth ranges")
# and --large-grid (doc/dirt-trace.md, "The large primitives' grid"), each on
# its own against all off.
#  - Work (--count-work, one run per arm; counts, fine on a loaded machine):
#    per ray type tiles walked, Hi-Z steps and triangle tests per ray.
#  - Time (REPEATS > 0; a quiet machine or a lent GPU): dirt-render of the
#    arms interleaved (off, each option, off, ...), REPEATS times after one
#    uncounted warm-up round (shader and file caches); per scene
#    and arm the minimum over the repeats of the frame (build + SPP samples,
#    total_ms), of the traces (trace_ms) and of the build (build_ms), and
#    arm / off. Every image must equal the off image bit for bit (checked:
#    exit 1 if not).
# perf/gpu-check.sh runs it on the lent GPU. Record figures with their
# command, machine and driver in perf/results/.
#
#   [OPTIONS='--bucket-masks --sub-tiles --node-depths --large-grid'] \
#   perf/bench-options.sh [BUILD_DIR] [WxH] [SPP] [REPEATS] [SCENE...]
#   (defaults build 256x192 4 3 default; REPEATS 0: the counts only)
set -euo pipefail
build=${1:-build}
res=${2:-256x192}
spp=${3:-4}
reps=${4:-3}
shift $(( $# > 4 ? 4 : $# ))
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default)
read -r -a opts <<<"${OPTIONS:---bucket-masks --sub-tiles --node-depths --large-grid}"
render=$build/src/app/dirt-render
cmp=$build/test/e2e/exr_compare
[ -x "$render" ] || { echo "bench-options: no $render" >&2; exit 2; }
py=${PYTHON:-$(if [ -x /usr/bin/python3 ]; then echo /usr/bin/python3; else echo python3; fi)}
tmp=$(mktemp -d /tmp/dirt-bench-options-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
W=${res%x*} H=${res#*x}
arms=(off "${opts[@]}")
status=0
flag() { [ "$1" = off ] || printf '%s' "$1"; }

echo "Work per ray at $W x $H (the hit-agreement rays of each type), DIRT with all off and with each option"
echo
echo "| scene | ray type | arm | tiles | Hi-Z steps | list nodes | tri tests | tiles / off | tests / off |"
echo "|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for i in "${!arms[@]}"; do
    f=$(flag "${arms[$i]}")
    "$render" "$s" --engine dirt -W "$W" -H "$H" --spp 1 --count-work ${f:+"$f"} \
      -o "$tmp/w$i.png" --stats "$tmp/w$i.json" -q
  done
  "$py" - "$tmp" "$(basename "$s")" "${arms[@]}" <<'PY'
import json, sys
tmp, name, arms = sys.argv[1], sys.argv[2], sys.argv[3:]
work = [json.load(open(f"{tmp}/w{i}.json"))["frames"][0]["work"] for i in range(len(arms))]
for t, a in work[0].items():
    for arm, w in zip(arms, work):
        b, n = w[t], max(w[t]["rays"], 1)
        print(f"| {name} | {t} | {arm} | {b['tiles'] / n:.3f} | {b['hiz_steps'] / n:.2f} | "
              f"{b['list_nodes'] / n:.2f} | {b['triangle_tests'] / n:.2f} | "
              f"{b['tiles'] / max(a['tiles'], 1):.3f} | "
              f"{b['triangle_tests'] / max(a['triangle_tests'], 1):.3f} |")
PY
done
[ "$reps" -gt 0 ] || exit 0

echo
echo "Time at $W x $H, $spp spp, 4 bounces; minimum of $reps interleaved runs each"
echo
echo "| scene | arm | frame ms | / off | traces ms | / off | build ms | / off |"
echo "|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for r in $(seq 0 "$reps"); do # (round 0: a warm-up, not counted)
    for i in "${!arms[@]}"; do
      f=$(flag "${arms[$i]}")
      "$render" "$s" --engine dirt -W "$W" -H "$H" --spp "$spp" ${f:+"$f"} \
        -o "$tmp/i$i.exr" --stats "$tmp/t$i-$r.json" -q
      [ "$i" = 0 ] || "$cmp" --exact "$tmp/i0.exr" "$tmp/i$i.exr" >/dev/null ||
        { echo "$s: the image with ${arms[$i]} differs from the one without" >&2; status=1; }
    done
  done
  "$py" - "$tmp" "$reps" "$(basename "$s")" "${arms[@]}" <<'PY'
import json, sys
tmp, reps, name, arms = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
def best(i):
    f = [json.load(open(f"{tmp}/t{i}-{r}.json"))["frames"][0] for r in range(1, reps + 1)]
    return [min(x[k] for x in f) for k in ("total_ms", "trace_ms", "build_ms")]
base = best(0)
for i, arm in enumerate(arms):
    b = best(i)
    print(f"| {name} | {arm} | {b[0]:.1f} | {b[0] / base[0]:.3f} | {b[1]:.1f} | "
          f"{b[1] / base[1]:.3f} | {b[2]:.1f} | {b[2] / max(base[2], 1e-9):.3f} |")
PY
done
exit $status
