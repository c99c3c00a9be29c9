#!/usr/bin/env bash
# Two DIRT configurations side by side, with MMRT beside them: arm A and arm
# B are each a dirt-render binary and its extra options (two builds of the
# engine, or one build with and without an option). Per scene, the runs are
# interleaved (A, B, MMRT, A, B, MMRT, ...) REPEATS times, and the table
# gives the minimum over the repeats of the frame (build + SPP samples,
# total_ms), of the traces (trace_ms) and of the build (build_ms), B / A,
# and each arm's frame over MMRT's (issue 25's goal: at most 0.8). MMRT runs
# with arm A's binary. The images of A and B must be equal bit for bit
# (checked: exit 1 if not). Times: run it on a quiet machine and record the
# figures with the command, machine and driver in perf/results/.
#
#   A=BUILD_A[:OPTS] B=BUILD_B[:OPTS] perf/bench-ab.sh [WxH] [SPP] [REPEATS] [SCENE...]
#   e.g. A=build-main B=build perf/bench-ab.sh 256x192 4 5
#        A=build B='build:--large-grid' perf/bench-ab.sh
# With no SCENE: the default scene and perf/gen-scenes.sh's room69k,
# mirror69k and slats69k.
set -euo pipefail
res=${1:-256x192}
spp=${2:-4}
reps=${3:-5}
shift $(( $# > 3 ? 3 : $# ))
: "${A:?A=BUILD[:OPTS] is required}" "${B:?B=BUILD[:OPTS] is required}"
arm() { # arm NAME SPEC: NAME=(RENDER OPTS...)
  local build=${2%%:*} opts=
  [[ $2 == *:* ]] && opts=${2#*:}
  [ -x "$build/src/app/dirt-render" ] || { echo "bench-ab: no $build/src/app/dirt-render" >&2; exit 2; }
  read -r -a "$1" <<<"$build/src/app/dirt-render $opts"
}
arm a "$A"
arm b "$B"
cmp=${a[0]%/src/app/dirt-render}/test/e2e/exr_compare
tmp=$(mktemp -d /tmp/dirt-bench-ab-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
if [ $# -eq 0 ]; then
  "$(dirname "$0")/gen-scenes.sh" "$tmp" >/dev/null
  set -- default "$tmp"/room69k.gltf "$tmp"/mirror69k.glb "$tmp"/slats69k.glb
fi
W=${res%x*} H=${res#*x}
echo "A = $A; B = $B; $W x $H, $spp spp, 4 bounces; minimum of $reps interleaved runs each"
echo
echo "| scene | frame ms A | B | B / A | traces ms A | B | B / A | build ms A | B | MMRT frame ms | A / MMRT | B / MMRT |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
status=0
for s in "$@"; do
  for r in $(seq "$reps"); do
    "${a[0]}" "$s" --engine dirt -W "$W" -H "$H" --spp "$spp" "${a[@]:1}" \
      -o "$tmp/a.exr" --stats "$tmp/a$r.json" -q
    "${b[0]}" "$s" --engine dirt -W "$W" -H "$H" --spp "$spp" "${b[@]:1}" \
      -o "$tmp/b.exr" --stats "$tmp/b$r.json" -q
    "${a[0]}" "$s" --engine mmrt -W "$W" -H "$H" --spp "$spp" \
      -o "$tmp/m.exr" --stats "$tmp/m$r.json" -q
    "$cmp" --exact "$tmp/a.exr" "$tmp/b.exr" >/dev/null ||
      { echo "$s: B's image differs from A's" >&2; status=1; }
  done
  /usr/bin/python3 - "$tmp" "$reps" "$(basename "$s")" <<'PY'
import json, sys
tmp, reps, name = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def best(arm):
    f = [json.load(open(f"{tmp}/{arm}{r}.json"))["frames"][0] for r in range(1, reps + 1)]
    return [min(x[k] for x in f) for k in ("total_ms", "trace_ms", "build_ms")]
a, b, m = best("a"), best("b"), best("m")
print(f"| {name} | {a[0]:.1f} | {b[0]:.1f} | {b[0] / a[0]:.3f} | {a[1]:.1f} | {b[1]:.1f} | "
      f"{b[1] / a[1]:.3f} | {a[2]:.1f} | {b[2]:.1f} | {m[0]:.1f} | {a[0] / m[0]:.3f} | "
      f"{b[0] / m[0]:.3f} |")
PY
done
exit $status
