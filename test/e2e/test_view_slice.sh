#!/usr/bin/env bash
# dirt-view answers between the slices of one sample: in a real window under
# Xvfb, with one smallest piece of the sample a frame (--slice-ms 0) and
# every frame made 0.3 s slower (the test hook DIRT_VIEW_SLOW_FRAME_MS), a
# real key press (2: the albedo buffer) sent with xdotool while the first
# sample is in progress takes effect before that sample completes: the
# report after it shows the albedo, still 0 samples and more of the sample
# done than before the key; the frame log (DIRT_VIEW_FRAME_LOG) shows the
# frame that changed the buffer in the sample's midst. Without slices (a
# whole sample a frame) the first frame completes the sample and this fails.
# Then the automatic scale: on a software renderer (llvmpipe, lavapipe) a
# 1280x720 window renders at window / N (N > 1) without --scale, says so,
# and a sample spans several frames; --scale 1 renders 1:1. Embree's
# sample spans frames too (pieces of tiles).
# Last, a panel click acts in the frame that sees it: with the panels at
# 1280x720 and frames 0.3 s slower, a real click (xdotool) on the Settings
# panel's collapse arrow shows the panel collapsed in the first frame that
# saw the button's release (the frame log's releases column), open in every
# frame before and collapsed in every one after (it toggled once). Without
# the panels' logic-only passes (dirt_ui_end_pass) the collapse shows two
# frames later and this fails.
# Before that, the raster preview fills the image until the first sample
# completes: a screenshot taken while the report says 0 samples is
# dirt-render's raster image of the reported camera.
#   test_view_slice.sh DIRT-VIEW DIRT-RENDER VIEW-CHECK
set -u
view=$1 render=$2 check=$3
tmp=$(mktemp -d /tmp/dirt-view-slice-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"

# 1. A key between the slices of one sample.
printf 'wait-frames 3\nreport %s\nwait-file %s\nwait-frames 3\nreport %s\nquit\n' \
  "$tmp/before.json" "$tmp/sent" "$tmp/after.json" >"$tmp/key.txt"
DIRT_VIEW_SLOW_FRAME_MS=300 DIRT_VIEW_FRAME_LOG="$tmp/frames.log" "$view" --window 320x240 \
  --scale 1 --no-ui --spp 1 --bounces 1 --slice-ms 0 --script "$tmp/key.txt" -q \
  >"$tmp/key.out" 2>&1 &
vpid=$!
for _ in $(seq 300); do [ -s "$tmp/before.json" ] && break; sleep 0.1; done
wid=$(xdotool search --name '^dirt-view' 2>/dev/null | head -n 1)
if [ -z "$wid" ] || [ ! -s "$tmp/before.json" ]; then fail "no window or no first report"; else
  xdotool key --window "$wid" 2
fi
touch "$tmp/sent"
wait "$vpid" || { fail "key run: exit $?"; cat "$tmp/key.out" >&2; }
python3 - "$tmp/before.json" "$tmp/after.json" "$tmp/frames.log" <<'PY' && ok ||
import json, sys
b, a = (json.load(open(p)) for p in sys.argv[1:3])
rows = [l.split() for l in open(sys.argv[3])]
print("before: %d samples, part %.4f, %s; after: %d samples, part %.4f, %s"
      % (b["samples"], b["sample_part"], b["buffer"], a["samples"], a["sample_part"], a["buffer"]))
bad = []
if not (b["samples"] == 0 and 0 < b["sample_part"] < 1 and b["buffer"] == "beauty"):
    bad.append("before the key: not 0 samples with a sample in progress, beauty")
if not (a["samples"] == 0 and b["sample_part"] < a["sample_part"] < 1):
    bad.append("after the key: the first sample is not still in progress, further on")
if a["buffer"] != "albedo":
    bad.append("the key did not act")
# the frame log: time frame samples part buffer panels settings-height
first = next((r for r in rows if r[4] == "albedo"), None)
if not first or int(first[2]) != 0 or not 0 < float(first[3]) < 1:
    bad.append("the log's first albedo frame %s is not in the first sample's midst" % first)
for m in bad:
    print(m)
sys.exit(1 if bad else 0)
PY
  fail "a key pressed in a sample's midst did not act before the sample completed"

# 1b. The raster preview before the first sample completes.
printf 'wait-frames 3\nscreenshot %s\nreport %s\nquit\n' "$tmp/pre.png" "$tmp/pre.json" >"$tmp/pre.txt"
DIRT_VIEW_SLOW_FRAME_MS=300 "$view" --window 160x120 --scale 1 --no-ui --spp 1 --slice-ms 0 \
  --script "$tmp/pre.txt" -q >"$tmp/pre.out" 2>&1 || { fail "preview run: exit $?"; cat "$tmp/pre.out" >&2; }
samples=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["samples"])' "$tmp/pre.json" 2>/dev/null)
args=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["render_args"])' "$tmp/pre.json" 2>/dev/null)
# shellcheck disable=SC2086
if [ "$samples" != 0 ]; then fail "the preview run's screenshot was not taken before the first sample ($samples)"
elif ! "$render" $args --engine raster -q --png -o "$tmp/raster.exr"; then fail "dirt-render --engine raster"
elif "$check" zoom "$tmp/pre.png" "$tmp/raster.png" 0 0 1; then ok
else fail "before the first sample, the window is not the raster preview of the camera"; fi

# 2. The automatic scale on a software renderer.
printf 'wait-samples 1\nwait-frames 1\nreport %s\nquit\n' "$tmp/auto.json" >"$tmp/auto.txt"
DIRT_VIEW_FRAME_LOG="$tmp/auto.log" "$view" --window 1280x720 --no-ui --spp 1 \
  --script "$tmp/auto.txt" >"$tmp/auto.out" 2>&1 || { fail "auto run: exit $?"; cat "$tmp/auto.out" >&2; }
printf 'wait-frames 2\nreport %s\nquit\n' "$tmp/one.json" >"$tmp/one.txt"
"$view" --window 1280x720 --no-ui --spp 1 --scale 1 --script "$tmp/one.txt" -q \
  >"$tmp/one.out" 2>&1 || { fail "--scale 1 run: exit $?"; cat "$tmp/one.out" >&2; }
python3 - "$tmp/auto.json" "$tmp/auto.out" "$tmp/auto.log" "$tmp/one.json" <<'PY' && ok ||
import json, sys
a = json.load(open(sys.argv[1]))
log = open(sys.argv[2]).read()
rows = [l.split() for l in open(sys.argv[3])]
one = json.load(open(sys.argv[4]))
soft = any(k in a["device"] for k in ("llvmpipe", "lavapipe", "softpipe"))
frames = sum(1 for r in rows if int(r[2]) == 0)
print("%s: scale %d (auto %s), render %s, %d frames before the first sample, its time %.0f ms"
      % (a["device"], a["scale"], a["scale_auto"], a["render"], frames, a["last_sample_ms"]))
bad = []
if soft:
    n = a["scale"]
    if not (a["scale_auto"] and n > 1 and a["render"] == [1280 // n, 720 // n]):
        bad.append("no automatic scale on a software renderer")
    if "software renderer" not in log or "window's size / %d" % n not in log:
        bad.append("the log does not say which scale and why")
    if frames < 3:
        bad.append("the first sample did not span several frames")
elif a["scale"] != 1 or a["scale_auto"]:
    bad.append("a scale other than 1 on a hardware GPU")
if one["scale"] != 1 or one["scale_auto"] or one["render"] != [1280, 720]:
    bad.append("--scale 1 does not render 1:1: %s" % one["render"])
for m in bad:
    print(m)
sys.exit(1 if bad else 0)
PY
  fail "the automatic scale"

# 2b. Embree slices too: with --slice-ms 0 (one 16 x 16 tile a frame) its
# first sample at 160x120 (80 tiles) spans many frames, each logged with
# a part in (0, 1) and 0 samples until it completes.
printf 'wait-samples 1\nwait-frames 1\nquit\n' >"$tmp/embree.txt"
DIRT_VIEW_FRAME_LOG="$tmp/embree.log" "$view" --window 160x120 --scale 1 --no-ui --spp 2 \
  --engine embree --slice-ms 0 --script "$tmp/embree.txt" -q >"$tmp/embree.out" 2>&1 ||
  { fail "embree run: exit $?"; cat "$tmp/embree.out" >&2; }
python3 - "$tmp/embree.log" <<'PY' && ok ||
import sys
rows = [l.split() for l in open(sys.argv[1])]
mid = [r for r in rows if int(r[2]) == 0 and 0 < float(r[3]) < 1]
print("embree: %d frames in its first sample's midst, %d frames" % (len(mid), len(rows)))
sys.exit(0 if len(mid) >= 20 and any(int(r[2]) == 1 for r in rows) else 1)
PY
  fail "embree's first sample did not span frames"

# 3. A panel click shown in the frame that saw it.
printf 'wait-frames 3\nreport %s\nwait-file %s\nwait-frames 3\nquit\n' \
  "$tmp/click-before.json" "$tmp/clicked" >"$tmp/click.txt"
DIRT_VIEW_SLOW_FRAME_MS=300 DIRT_VIEW_FRAME_LOG="$tmp/click.log" "$view" --window 1280x720 \
  --spp 1048576 --slice-ms 0 --script "$tmp/click.txt" -q >"$tmp/click.out" 2>&1 &
vpid=$!
for _ in $(seq 300); do [ -s "$tmp/click-before.json" ] && break; sleep 0.1; done
wid=$(xdotool search --name '^dirt-view' 2>/dev/null | head -n 1)
if [ -z "$wid" ] || [ ! -s "$tmp/click-before.json" ]; then fail "click run: no window or no report"; else
  xdotool mousemove --window "$wid" 17 17
  sleep 0.7
  xdotool click 1
  sleep 0.7
fi
touch "$tmp/clicked"
wait "$vpid" || { fail "click run: exit $?"; cat "$tmp/click.out" >&2; }
python3 - "$tmp/click.log" <<'PY' && ok ||
import sys
# time frame samples part buffer panels settings-height releases logic-passes
rows = [l.split() for l in open(sys.argv[1])]
i = next((k for k, r in enumerate(rows) if int(r[7]) > 0), None)
bad = []
if i is None or i == 0:
    bad.append("no frame saw the click's release (or the first one did)")
else:
    open_h, h = float(rows[0][6]), float(rows[i][6])
    print("Settings %.0f px high before the click; the frame that saw its release (%d of %d): "
          "%.0f px, %s logic-only passes so far" % (open_h, i, len(rows), h, rows[i][8]))
    if any(float(r[6]) != open_h for r in rows[:i]):
        bad.append("the panel changed before the click was seen")
    if not h < open_h / 4:
        bad.append("the frame that saw the click does not show the panel collapsed")
    if any(float(r[6]) != h for r in rows[i:]):
        bad.append("the panel did not stay collapsed after the click (toggled more than once?)")
    if len(rows) - i < 3:
        bad.append("too few frames after the click")
for m in bad:
    print(m)
sys.exit(1 if bad else 0)
PY
  fail "a panel click did not show in the frame that saw it"

echo "test_view_slice: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
