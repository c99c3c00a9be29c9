#!/usr/bin/env bash
# Work per ray (--count-work; doc/dirt-trace.md, "Work counters"): DIRT vs
# MMRT vs Embree's BVH over the same rays, per ray type, on the default
# scene, the generated scenes nobody tuned for (perf/gen-scenes.sh: a closed
# room with dense geometry, the same kind of geometry over a mirror floor,
# thin slats at grazing angles) and any SCENE given. Counts, not times:
# deterministic, so any machine may record them
# (perf/results/work-llvmpipe.md).
#
#   perf/bench-work.sh [BUILD_DIR] [WxH] [SCENE...]
#
# EXTRA: more dirt-render options for DIRT's runs (MMRT's take none), e.g.
#   EXTRA='--sub-tiles' perf/bench-work.sh build 128x96
set -euo pipefail
build=${1:-build}
res=${2:-128x96}
shift $(( $# > 2 ? 2 : $# ))
render=$build/src/app/dirt-render
tmp=$(mktemp -d /tmp/dirt-bench-work-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
"$(dirname "$0")/gen-scenes.sh" "$tmp" >/dev/null
scenes=(default "$tmp"/room69k.gltf "$tmp"/mirror69k.glb "$tmp"/slats69k.glb "$@")
W=${res%x*} H=${res#*x}
echo "| scene | ray type | DIRT tri tests | tiles | Hi-Z steps | list nodes | MMRT fragments | MMRT Hi-Z steps | Embree tri tests | Embree BVH nodes | DIRT / Embree tri tests |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
read -ra extra <<< "${EXTRA:-}"
for s in "${scenes[@]}"; do
  for e in dirt mmrt; do
    more=(); [ $e = dirt ] && more=("${extra[@]}")
    "$render" "$s" --engine $e -W "$W" -H "$H" --spp 1 --count-work -o "$tmp/$e.png" \
      --stats "$tmp/$e.json" -q "${more[@]}"
  done
  python3 - "$tmp/dirt.json" "$tmp/mmrt.json" "$(basename "$s")" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["frames"][0]["work"]
m = json.load(open(sys.argv[2]))["frames"][0]["work"]
for t, w in d.items():
    n, e, mm = w["rays"], w["embree"], m[t]
    print("| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |" % (
        sys.argv[3], t, w["triangle_tests"] / n, w["tiles"] / n, w["hiz_steps"] / n,
        w["list_nodes"] / n, mm["fragments"] / mm["rays"], mm["hiz_steps"] / mm["rays"],
        e["triangle_tests"] / n, e["bvh_nodes"] / n, w["triangle_tests"] / e["triangle_tests"]))
PY
done
