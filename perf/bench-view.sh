#!/usr/bin/env bash
# The displayed frame time of dirt-view while it path traces: per window
# size and engine, dirt-view runs FRAMES frames (panels shown, rendering at
# the window's size: --scale 1; a frame traces a slice of --slice-ms of a
# sample, or one whole sample of embree and raster) under xvfb-run and reports the frame and sample times (min,
# median, max over the frames after the first). The configurations run
# interleaved, REPEATS times each; the table keeps each one's minimum of
# the medians. Prints a markdown table with the machine and renderer.
#   [SIZES="WxH ..."] [ENGINES="dirt ..."] perf/bench-view.sh BUILD_DIR [FRAMES] [REPEATS] [SCENE]
set -eu
build=$1 frames=${2:-40} repeats=${3:-3} scene=${4:-}
view=$build/src/app/dirt-view
tmp=$(mktemp -d /tmp/bench-view-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
sizes=${SIZES:-"320x240 640x480 1280x720"}
engines=${ENGINES:-"dirt mmrt raster"}
for r in $(seq "$repeats"); do
  for size in $sizes; do
    for engine in $engines; do
      # shellcheck disable=SC2086
      xvfb-run -a -s "-screen 0 1600x1000x24" "$view" $scene --window "$size" \
        --engine "$engine" --scale 1 --spp 1048576 --test-frames "$frames" -q \
        --report "$tmp/$size-$engine-$r.json"
    done
  done
done
python3 - "$tmp" "$repeats" "$sizes" "$engines" "$frames" <<'PY'
import json, sys, platform, subprocess
tmp, repeats, sizes, engines, frames = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(), sys.argv[4].split(), sys.argv[5]
rows, device, clock = [], "", ""
for size in sizes:
    for engine in engines:
        reps = [json.load(open(f"{tmp}/{size}-{engine}-{r}.json")) for r in range(1, repeats + 1)]
        device, clock = reps[0]["device"], reps[0]["clock"]
        best = min(reps, key=lambda j: j["frame_ms"]["median"])
        f, s = best["frame_ms"], best["samples_ms"]
        rows.append(f"| {size} | {engine} | {f['median']:.1f} | {f['min']:.1f} | {f['max']:.1f} | "
                    f"{s['median']:.1f} | {1000.0 / f['median']:.1f} |")
cpu = subprocess.run(["sh", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"],
                     capture_output=True, text=True).stdout.strip()
print(f"machine: {platform.node()} ({cpu}, {subprocess.run(['nproc'], capture_output=True, text=True).stdout.strip()} cores)")
print(f"renderer: {device}; pass clock: {clock}")
print(f"frames per run: {frames} (first excluded), repeats: {repeats}, interleaved; min of the medians\n")
print("| window = render | engine | frame ms (median) | min | max | samples ms (median) | fps |")
print("|---|---|---|---|---|---|---|")
print("\n".join(rows))
PY
