#!/usr/bin/env bash
# The prepared GPU check: what a lent NVIDIA machine runs in one call of
# under 9 minutes (doc/gpu-check.md), writing OUT/gpu-check.md (and the
# dirt-compare tables and the scaling benchmark under OUT/). Built here, carried there:
#   perf/gpu-pack.sh           collects the runtime libraries into .gpu/
#   carry: build .gpu .gl      (.gl: the GL loader packages, see doc/gpu-check.md)
#   perf/gpu-check.sh $OUT     there (also runs here, on llvmpipe, as a dry run)
# Parts (each under its own time limit, so one hang cannot eat the call):
#   1. the device: nvidia-smi, the renderer and EGL platform the engine gets,
#      and the driver facts (gpu-facts: conservative raster extensions,
#      storage block and texel-buffer limits, timer bits and resolution);
#   2. the GPU tests, run directly (no meson there), conservative raster
#      (extension vs emulation: the same lists) included;
#   3. the build and trace at 1024x512: DIRT build per pass (bench-ads, the
#      raster build; S = 1, 2), raster against compute build (bench-build),
#      DIRT vs MMRT (dirt-compare, no quality, with the frame ratio), and
#      Mrays/s per ray type, DIRT on the GPU vs Embree on the CPU's cores
#      (bench-trace);
#   4. DIRT's trace options on and off (perf/bench-options.sh:
#      --bucket-masks, --sub-tiles, --node-depths, --large-grid; counts and
#      times);
#   5. the scaling benchmark (perf/bench-scale.py: 10^4..10^7 triangles at
#      1920x1080, 0.1..8 MP at 10^6, both DIRT builds, MMRT, Embree and the
#      raster preview; the scenes are made there, which needs python3-numpy;
#      SCALE_ARGS replaces its grid, and on a software renderer it is the
#      --quick one).
set -u
out=${1:?usage: perf/gpu-check.sh OUTDIR [SCENE...]}
shift
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
mkdir -p "$out"
report=$out/gpu-check.md
[ -d "$root/.gpu/lib" ] && export LD_LIBRARY_PATH=$root/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export DIRT_GLSL_DIR=$root/glsl
export DIRT_SHARED_DIR=${DIRT_SHARED_DIR:-$root/../shared}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default)
res=${RES:-1024x512}
W=${res%x*} H=${res#*x}
start=$(date +%s)
say() { printf '%s\n' "$*" | tee -a "$report"; }
# part NAME LIMIT CMD...: runs CMD with a time limit, its output in the report.
part() {
  local name=$1 limit=$2; shift 2
  say ""; say "### $name"; say ""; say '```'
  say "\$ $*"
  timeout "$limit" "$@" >"$out/part.log" 2>&1
  local rc=$?
  tail -n 60 "$out/part.log" | tee -a "$report"
  say '```'
  say "exit $rc$( [ $rc = 124 ] && echo ' (time limit)')"
  return $rc
}
: >"$report"
say "# GPU check ($(date -u +%Y-%m-%dT%H:%M:%SZ), commit $(git -C "$root" describe --always --dirty 2>/dev/null || echo unknown))"
part "device" 30 sh -c "nvidia-smi -L 2>/dev/null || echo 'no nvidia-smi'; \
  '$build/src/app/dirt-render' -o '$out/probe.png' -W 64 --spp 1 2>&1 | head -n 3"
part "driver facts (gpu-facts)" 30 "$build/perf/gpu-facts"
software=0
grep -qiE "llvmpipe|softpipe|lavapipe" "$out/part.log" && software=1

say ""; say "### GPU tests"; say ""
say "| test | result | seconds |"; say "|---|---|---|"
for t in gl_context timing layout_gpu conservative_raster ads_complete ads_edge ads_clip ads_compute ads_large dirt_hits \
         bucket_masks ads_sub_tiles trace_work \
         dirt_visibility dirt_fetch dirt_pt pt_compact mmrt_hits mmrt_store mmrt_trace mmrt_pt session memory; do
  exe=$build/test/gpu/test_$t
  [ -x "$exe" ] || { say "| $t | missing | |"; continue; }
  # The tests get 120 s in all (the call's 5 minutes hold the benches too).
  if [ $(( $(date +%s) - start )) -gt 150 ]; then say "| $t | not run (the tests' 120 s are up) | |"; continue; fi
  t0=$(date +%s.%N)
  timeout 60 "$exe" >"$out/test_$t.log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
  case $rc in 0) r=pass ;; 77) r=skip ;; 124) r="time limit" ;; *) r="FAIL ($rc)" ;; esac
  say "| $t | $r | $(printf '%.1f' "$(echo "$t1 - $t0" | bc)") |"
  [ "$rc" = 0 ] || [ "$rc" = 77 ] || tail -n 15 "$out/test_$t.log" >>"$report"
done
[ -x "$build/perf/bench-ads" ] &&
  part "DIRT build per pass, $res (bench-ads)" 90 "$build/perf/bench-ads" "${scenes[@]}" \
    -W "$W" -H "$H" -S 1,2 -B 16 --repeat 3
# The default build per device comes from this: raster (the paper's
# pipeline, hardware conservative raster) against compute passes.
[ -x "$build/perf/bench-build" ] &&
  part "DIRT raster vs compute build, $res (bench-build)" 60 "$build/perf/bench-build" \
    "${scenes[@]}" -W "$W" -H "$H" --views cube+camera -S 1,2 -B 16 --repeat 3 --build both
part "DIRT vs MMRT, $res (dirt-compare, no quality)" 150 "$build/src/app/dirt-compare" \
  "${scenes[@]}" -o "$out/compare" --res "$res" --tile 1,2 --repeat 3 --no-quality -q
[ -f "$out/compare/table.md" ] && { say ""; cat "$out/compare/table.md" >>"$report"; }
[ -x "$build/perf/bench-trace" ] &&
  part "Mrays/s per ray type, $res: DIRT (GPU) vs Embree ($(nproc) CPU threads)" 90 \
    "$build/perf/bench-trace" "${scenes[@]}" -W "$W" -H "$H"
# The trace options that are bets on a GPU (off by default; on llvmpipe
# they cost time): --bucket-masks, --sub-tiles, --node-depths and --large-grid, each on
# against all off, counts and times (the images checked bit for bit), on the
# check's scenes and mirror69k (made here, as perf/gen-scenes.sh does; the
# masks skip the most tiles there). OPT_REPS repeats (3; 1 on a software
# renderer).
py=${PYTHON:-$(if [ -x /usr/bin/python3 ]; then echo /usr/bin/python3; else echo python3; fi)}
opt_scenes=("${scenes[@]}")
mkdir -p "$out/scenes"
timeout 60 "$py" "$root/perf/make-scale-scene.py" "$out/scenes/mirror69k.glb" 69000 --kind mirror \
  >/dev/null 2>&1 && opt_scenes+=("$out/scenes/mirror69k.glb")
part "DIRT options on/off, $res: --bucket-masks, --sub-tiles, --node-depths, --large-grid (bench-options)" 150 \
  "$root/perf/bench-options.sh" "$build" "$res" 4 "${OPT_REPS:-$([ $software = 1 ] && echo 1 || echo 3)}" \
  "${opt_scenes[@]}"
# (the part shows the last 60 lines; the whole tables beside the report)
cp "$out/part.log" "$out/bench-options.md"
[ "$(wc -l <"$out/bench-options.md")" -le 60 ] ||
  { say ""; say "(the whole output: bench-options.md)"; cat "$out/bench-options.md" >>"$report"; }
rm -rf "$out/scenes"
# The scaling benchmark: on a GPU its own grid; a software renderer's dry
# run takes the --quick one.
if [ -n "${SCALE_ARGS:-}" ]; then
  read -r -a scale_args <<<"$SCALE_ARGS"
elif [ $software = 1 ]; then
  scale_args=(--quick)
else
  scale_args=(--triangles 1e4,1e5,1e6,1e7 --fixed-res 1920x1080 --fixed-triangles 1e6
              --res 368x276,1280x720,1920x1080,3840x2160 --frames 2
              --engines dirt-raster,dirt-compute,mmrt,embree,raster --timeout 60)
fi
# (py: Debian's python3, which has numpy, before another python3 on PATH)
part "scaling (bench-scale)" 200 "$py" "$root/perf/bench-scale.py" "$out/scale" \
  --render "$build/src/app/dirt-render" "${scale_args[@]}"
[ -f "$out/scale/table.md" ] && { say ""; cat "$out/scale/table.md" >>"$report"; }
say ""; say "total: $(( $(date +%s) - start )) s"
rm -f "$out/part.log"
