#!/usr/bin/env bash
# dirt-view as a person uses it, in a real window under xvfb-run:
#  - after N samples --save-image equals dirt-render's image with the same
#    scene, size, camera, seed and settings (dirt and mmrt), bit for bit;
#  - a window screenshot holds the panels (different from the render there)
#    and the render (equal to the saved image where no panel covers it);
#    the depth buffer shows the image's Z through the heat ramp;
#  - real X input (xdotool: a left drag, the wheel, a held key) moves the
#    camera, and dirt-render from the camera the viewer reports gives the
#    viewer's image; the script's orbit does the same;
#  - a resize changes the render size and the render follows;
#  - animation: the timeline and playing move the time, and the image at
#    the reported time equals dirt-render -t (BoxAnimated from ../shared);
#  - a saved EXR's header records what made it (read with OpenEXR's API),
#    its dirt-render options among them;
#  - a bad scene, option, script or output path exits 2 before a window.
#   test_view.sh DIRT-VIEW DIRT-RENDER VIEW_CHECK DOC/VIEWER.MD EXR_COMPARE
set -u
view=$1 render=$2 check=$3 doc=$4 exr=$5
tmp=$(mktemp -d /tmp/dirt-view-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }

# One X server for the whole test (view_xvfb.sh).
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"

# run_view NAME ARGS...: dirt-view with its output in $tmp/NAME.{out,err}, at
# scale 1 (llvmpipe would otherwise render at the window / N that makes a
# sample take about 1 s; the tests compare the render with the window's size).
run_view() {
  local name=$1; shift
  "$view" "$@" --scale 1 >"$tmp/$name.out" 2>"$tmp/$name.err"
}
json_field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

# 1. The saved image equals dirt-render's (the render follows the 160x120 window).
for engine in dirt mmrt; do
  printf 'wait-samples 3\nquit\n' >"$tmp/s.txt"
  if run_view "same-$engine" --window 160x120 --no-ui --engine $engine --seed 7 --bounces 3 \
      --script "$tmp/s.txt" --save-image "$tmp/v-$engine.exr" --report "$tmp/v-$engine.json" -q
  then ok; else fail "$engine: dirt-view exit $?"; cat "$tmp/same-$engine.err" >&2; fi
  spp=$(json_field "$tmp/v-$engine.json" samples)
  [ "$spp" = 3 ] && ok || fail "$engine: the viewer saved $spp samples, not the 3 waited for"
  "$render" -W 160 -H 120 --engine $engine --seed 7 --bounces 3 --spp 3 -q \
    -o "$tmp/r-$engine.exr" || fail "$engine: dirt-render failed"
  if "$check" same "$tmp/v-$engine.exr" "$tmp/r-$engine.exr"; then ok; else
    fail "$engine: the viewer's image is not dirt-render's"; fi
done
[ -s "$tmp/v-dirt.png" ] && ok || fail "--save-image X.exr wrote no PNG beside it"
# The saved EXR's provenance: this run's engine, seed and samples, its command
# line, and the dirt-render options of the image.
"$exr" --attrs "$tmp/v-mmrt.exr" dirt.scene dirt.engine dirt.seed dirt.samples dirt.time \
  dirt.device dirt.command_line dirt.version dirt.commit dirt.render_args >"$tmp/attrs" &&
  grep -qx 'dirt.engine=mmrt' "$tmp/attrs" && grep -qx 'dirt.seed=7' "$tmp/attrs" &&
  grep -qx 'dirt.samples=3' "$tmp/attrs" && grep -qx 'dirt.scene=default' "$tmp/attrs" &&
  grep -q '^dirt.command_line=.*dirt-view --window 160x120 --no-ui --engine mmrt --seed 7' "$tmp/attrs" &&
  grep -q '^dirt.render_args=-W 160 -H 120 --engine mmrt --seed 7 --bounces 3' "$tmp/attrs" && ok ||
  { fail "the saved EXR's provenance"; cat "$tmp/attrs" >&2; }

# 2. A screenshot holds the panels and the render.
printf 'wait-samples 2\nscreenshot %s\nsave-image %s\nreport %s\nquit\n' \
  "$tmp/shot.png" "$tmp/alone.png" "$tmp/rep.json" >"$tmp/s.txt"
# (Slices of 200 ms: at 900x600 with the panels a frame's drawing on llvmpipe
# costs about as much as a default 30 ms slice; this checks the picture.)
if run_view shot --window 900x600 --slice-ms 200 --script "$tmp/s.txt" -q; then ok; else
  fail "screenshot run: exit $?"; cat "$tmp/shot.err" >&2; fi
if "$check" window "$tmp/shot.png" "$tmp/alone.png" "$tmp/rep.json"; then ok; else
  fail "the screenshot is not the render plus the panels"; fi

# 2a. At a small window (480x360) the panels start collapsed to their title
# bars: the image is the render wherever they used to cover it (all of it),
# and the panels take less than a tenth of the window.
printf 'wait-samples 1\nscreenshot %s\nsave-image %s\nreport %s\nquit\n' \
  "$tmp/small.png" "$tmp/small-alone.png" "$tmp/small.json" >"$tmp/s.txt"
if run_view small --window 480x360 --bounces 1 --script "$tmp/s.txt" -q; then ok; else
  fail "small-window run: exit $?"; cat "$tmp/small.err" >&2; fi
if "$check" window "$tmp/small.png" "$tmp/small-alone.png" "$tmp/small.json" collapsed; then ok; else
  fail "at 480x360 the screenshot is not the render plus the panels"; fi
python3 - "$tmp/small.json" <<'PY' && ok || fail "at 480x360 the panels cover the image"
import json, sys
r = json.load(open(sys.argv[1]))
# the part of each panel inside the window (a panel may reach past its edge)
clip = lambda a, w, lim: max(0, min(a + w, lim) - max(a, 0))
area = sum(clip(p[0], p[2], 480) * clip(p[1], p[3], 360) for p in r["panels"])
print("panels", r["panels"], "cover %.1f%% of 480x360" % (100 * area / (480 * 360)))
sys.exit(0 if r["panels"] and area < 0.1 * 480 * 360 else 1)
PY

# 2c. No label is cut off: at 1280x720 with every section of every panel
# open (test hook DIRT_VIEW_OPEN_HEADERS) and the bookmarks panel open (a
# real click on its title bar), and at 480x360 with the Numbers panel open
# (a real click), no widget with its label, checkbox, button or label line
# reaches past its panel's edge (labels that do not fit beside their widget
# go above it; text wraps), and the panels lie inside the window.
for case in "1280x720 924 445 3" "480x360 196 43 1"; do
  set -- $case
  rm -f "$tmp/lgo"
  printf 'wait-samples 1\nwait-file %s\nwait-frames 3\nscreenshot %s\nreport %s\nquit\n' \
    "$tmp/lgo" "$tmp/labels-$1.png" "$tmp/labels-$1.json" >"$tmp/s.txt"
  DIRT_VIEW_OPEN_HEADERS=1 "$view" --window "$1" --scale 8 --spp 1 --bounces 1 \
    --script "$tmp/s.txt" -q >"$tmp/labels.out" 2>&1 &
  vpid=$!
  wid=$(window_id)
  sleep 2
  [ -n "$wid" ] && xdotool mousemove --window "$wid" "$2" "$3" click 1
  sleep 1; touch "$tmp/lgo"
  wait "$vpid" || { fail "labels run at $1: exit $?"; cat "$tmp/labels.out" >&2; }
  python3 - "$tmp/labels-$1.json" "$4" <<'PY' && ok || fail "labels cut off at $1"
import json, sys
r = json.load(open(sys.argv[1]))
w, h = r["window"]
opened = [p for p in r["panels"] if p[3] > 60]
print(r["window"], "clipped labels", r["clipped_labels"], "panels", r["panels"])
bad = r["clipped_labels"] != 0 or len(opened) != int(sys.argv[2])
bad |= any(p[0] < 0 or p[1] < 0 or p[0] + p[2] > w or p[1] + p[3] > h for p in r["panels"])
sys.exit(1 if bad else 0)
PY
done

# 2b. The depth buffer shown as a heat map is the image's Z through the ramp.
printf 'wait-samples 1\nset buffer depth\nwait-frames 1\nscreenshot %s\nsave-image %s\nquit\n' \
  "$tmp/depth-shot.png" "$tmp/depth.exr" >"$tmp/s.txt"
run_view depth --window 160x120 --no-ui --script "$tmp/s.txt" -q || fail "depth run failed"
if "$check" heat "$tmp/depth-shot.png" "$tmp/depth.exr"; then ok; else
  fail "the depth heat map is not the image's Z through the ramp"; fi

# 3. Real input moves the camera: a left drag, the wheel and a held key.
printf 'wait-file %s\nwait-frames 3\nwait-samples 2\nsave-image %s\nreport %s\nquit\n' \
  "$tmp/go" "$tmp/moved.exr" "$tmp/moved.json" >"$tmp/s.txt"
"$view" --window 200x150 --scale 1 --no-ui --seed 3 --bounces 2 --script "$tmp/s.txt" \
  >"$tmp/input.out" 2>"$tmp/input.err" &
vpid=$!
wid=$(window_id)
if [ -z "$wid" ]; then fail "no dirt-view window appeared"; else
  sleep 1
  xdotool mousemove --window "$wid" 100 75; sleep 0.3
  xdotool mousedown 1; sleep 0.3
  for _ in 1 2 3 4 5; do xdotool mousemove_relative -- 12 4; sleep 0.15; done
  xdotool mouseup 1; sleep 0.3
  xdotool click 4; sleep 0.3
  xdotool keydown d; sleep 0.4; xdotool keyup d; sleep 0.3
fi
touch "$tmp/go"
if wait "$vpid"; then ok; else fail "input run: exit $?"; cat "$tmp/input.err" >&2; fi
cam=$(json_field "$tmp/moved.json" camera_args 2>/dev/null)
mode=$(json_field "$tmp/moved.json" camera_mode 2>/dev/null)
[ "$mode" = look ] && ok || fail "after the drag the camera mode is '$mode', not look"
# shellcheck disable=SC2086
spp=$(json_field "$tmp/moved.json" samples 2>/dev/null)
# shellcheck disable=SC2086
"$render" -W 200 -H 150 --seed 3 --bounces 2 --spp "$spp" -q $cam -o "$tmp/moved-r.exr" ||
  fail "dirt-render $cam failed"
if "$check" same "$tmp/moved.exr" "$tmp/moved-r.exr"; then ok; else
  fail "dirt-render from the reported camera ($cam) is not the viewer's image"; fi
"$render" -W 200 -H 150 --seed 3 --bounces 2 --spp "$spp" -q -o "$tmp/unmoved.exr"
if "$check" same "$tmp/moved.exr" "$tmp/unmoved.exr" >/dev/null; then
  fail "the input did not move the camera"; else ok; fi
# The script's orbit, reported and rendered offline the same way.
printf 'orbit 40 15\ndolly 0.8\nwait-samples 2\nsave-image %s\nreport %s\nquit\n' \
  "$tmp/orbit.exr" "$tmp/orbit.json" >"$tmp/s.txt"
run_view orbit --window 200x150 --no-ui --script "$tmp/s.txt" -q || fail "orbit run failed"
cam=$(json_field "$tmp/orbit.json" camera_args 2>/dev/null)
spp=$(json_field "$tmp/orbit.json" samples 2>/dev/null)
# shellcheck disable=SC2086
"$render" -W 200 -H 150 --spp "$spp" -q $cam -o "$tmp/orbit-r.exr"
if "$check" same "$tmp/orbit.exr" "$tmp/orbit-r.exr"; then ok; else
  fail "script orbit: dirt-render $cam differs"; fi

# 3b. Double click focuses the thin lens at the surface under the cursor:
#     the focus distance is the image's Z there, and dirt-render with the
#     reported options (aperture and focus included) gives the same image.
printf 'set aperture 0.02\nwait-samples 1\nclick 60 50\nwait-frames 1\nwait-samples 2\nsave-image %s\nreport %s\nquit\n' \
  "$tmp/focus.exr" "$tmp/focus.json" >"$tmp/s.txt"
run_view focus --window 160x120 --no-ui --script "$tmp/s.txt" -q || fail "focus run failed"
# The Z AOV is traced along the lens centre's ray through the pixel centre,
# whose direction depends on the focus distance by float rounding (1e-7).
z=$("$check" pixel "$tmp/focus.exr" Z 60 50) focus=$(json_field "$tmp/focus.json" focus)
python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if abs(a - b) <= 1e-6 * b else 1)" \
  "$focus" "$z" && ok || fail "the focus $focus is not the Z $z under the cursor"
args=$(json_field "$tmp/focus.json" render_args) spp=$(json_field "$tmp/focus.json" samples)
# shellcheck disable=SC2086
"$render" $args --spp "$spp" -q -o "$tmp/focus-r.exr" || fail "dirt-render $args failed"
if "$check" same "$tmp/focus.exr" "$tmp/focus-r.exr"; then ok; else
  fail "dirt-render $args is not the focused image"; fi

# 4. A resize: the render follows the window.
printf 'wait-samples 1\nresize 300 200\nwait-frames 5\nwait-samples 1\nreport %s\nsave-image %s\nquit\n' \
  "$tmp/rs.json" "$tmp/rs.exr" >"$tmp/s.txt"
run_view resize --window 200x150 --no-ui --script "$tmp/s.txt" -q || fail "resize run failed"
size=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['render'])" "$tmp/rs.json")
[ "$size" = "[300, 200]" ] && ok || fail "after resize 300x200 the render is $size"
spp=$(json_field "$tmp/rs.json" samples)
"$render" -W 300 -H 200 --spp "$spp" -q -o "$tmp/rs-r.exr"
if "$check" same "$tmp/rs.exr" "$tmp/rs-r.exr"; then ok; else fail "the resized render differs"; fi

# 4b. Animation: the timeline (set time), a clip played with a speed; the
#     image at the time the viewer reports equals dirt-render -t at that time.
anim=${DIRT_SHARED_DIR:-../shared}/scenes/gltf/BoxAnimated/BoxAnimated.gltf
if [ ! -r "$anim" ]; then
  if [ "${CI:-}" = true ]; then fail "$anim missing (CI=true)"; else echo "no $anim: animation part skipped"; fi
else
  printf 'set time 0.75\nwait-samples 1\nsave-image %s\nreport %s\nset speed 2\nset play on\nwait-frames 3\nset play off\nwait-frames 1\nwait-samples 1\nsave-image %s\nreport %s\nquit\n' \
    "$tmp/t1.exr" "$tmp/t1.json" "$tmp/t2.exr" "$tmp/t2.json" >"$tmp/s.txt"
  run_view anim "$anim" --window 96x72 --no-ui --auto-camera --script "$tmp/s.txt" -q ||
    fail "animation run failed"
  t1=$(json_field "$tmp/t1.json" time) t2=$(json_field "$tmp/t2.json" time)
  [ "$t1" = 0.75 ] && ok || fail "set time 0.75 gave time $t1"
  python3 -c "import sys; sys.exit(0 if float(sys.argv[2]) > float(sys.argv[1]) else 1)" "$t1" "$t2" &&
    ok || fail "playing did not advance the time ($t1 -> $t2)"
  for k in 1 2; do
    t=$(json_field "$tmp/t$k.json" time) spp=$(json_field "$tmp/t$k.json" samples)
    "$render" "$anim" -W 96 -H 72 --auto-camera -t "$t" --spp "$spp" -q -o "$tmp/t$k-r.exr"
    if "$check" same "$tmp/t$k.exr" "$tmp/t$k-r.exr"; then ok; else
      fail "the viewer's frame at t=$t is not dirt-render -t $t"; fi
  done
fi

# 4c. The environment light: turned and dimmed while the window is open (the
#     map is remade), the saved image equals dirt-render with the reported
#     options; and it is not the image of the unturned map.
if [ -r "$anim" ]; then
  printf 'wait-samples 1\nset env-rotation 30\nset env-intensity 0.5\nwait-frames 1\nwait-samples 2\nsave-image %s\nreport %s\nquit\n' \
    "$tmp/env.exr" "$tmp/env.json" >"$tmp/s.txt"
  run_view env "$anim" --window 96x72 --no-ui --env sky --script "$tmp/s.txt" -q ||
    fail "environment run failed"
  args=$(json_field "$tmp/env.json" render_args) spp=$(json_field "$tmp/env.json" samples)
  case "$args" in *"--env sky --env-intensity 0.5 --env-rotation 30"*) ok ;;
    *) fail "render_args lack the environment: $args" ;; esac
  # shellcheck disable=SC2086
  "$render" "$anim" $args --spp "$spp" -q -o "$tmp/env-r.exr" || fail "dirt-render $args failed"
  if "$check" same "$tmp/env.exr" "$tmp/env-r.exr"; then ok; else
    fail "dirt-render $args is not the viewer's environment-lit image"; fi
  "$render" "$anim" -W 96 -H 72 --env sky --spp "$spp" -q -o "$tmp/env-0.exr"
  if "$check" same "$tmp/env.exr" "$tmp/env-0.exr" >/dev/null; then
    fail "turning and dimming the map changed nothing"; else ok; fi
fi

# 4d-4g. DIRT's trace options turned on while the window is open (the large
#     primitives' grid, sub-tile rectangles, bucket occupancy masks, node
#     depth ranges), each in
#     its own run: the structure is rebuilt, the image is the one without it
#     bit for bit (section 1's), and the reported options carry it.
for opt in large-grid sub-tiles bucket-masks node-depths; do
  printf 'wait-samples 1\nset %s on\nwait-frames 1\nwait-samples 3\nsave-image %s\nreport %s\nquit\n' \
    "$opt" "$tmp/$opt.exr" "$tmp/$opt.json" >"$tmp/s.txt"
  run_view "$opt" --window 160x120 --no-ui --engine dirt --seed 7 --bounces 3 --script "$tmp/s.txt" -q ||
    fail "$opt run failed"
  args=$(json_field "$tmp/$opt.json" render_args)
  case "$args" in *"--$opt"*) ok ;; *) fail "render_args lack --$opt: $args" ;; esac
  if "$check" same "$tmp/$opt.exr" "$tmp/v-dirt.exr"; then ok; else
    fail "the image with --$opt is not the one without"; fi
done

# 5. Bad input exits 2 with a one-line reason, before any window.
expect2() {
  local what=$1; shift
  "$view" "$@" >"$tmp/bad.out" 2>"$tmp/bad.err"
  local rc=$?
  if [ "$rc" -eq 2 ] && tail -n 1 "$tmp/bad.err" | grep -q '^dirt-view: '; then ok; else
    fail "$what: exit $rc, want 2 with a reason"; cat "$tmp/bad.err" >&2; fi
}
echo 'not a gltf' >"$tmp/bad.gltf"
expect2 "missing scene" "$tmp/none.glb" --test-frames 1
expect2 "malformed scene" "$tmp/bad.gltf" --test-frames 1
expect2 "missing environment map" --env "$tmp/none.exr" --test-frames 1
expect2 "--env and --background" --env sky --background 1,1,1 --test-frames 1
expect2 "bad option" --spp -3
expect2 "zero spp" --spp 0
expect2 "camera and auto camera" --camera 0 --auto-camera --test-frames 1
[ -r "$anim" ] && expect2 "scene over --max-scene-memory" "$anim" --max-scene-memory 1K --test-frames 1
[ -r "$anim" ] && { grep -q 'max-scene-memory' "$tmp/bad.err" && ok || fail "the budget's error"; }
expect2 "unknown option" --frobnicate
printf 'orbit 1\n' >"$tmp/bad.txt"
expect2 "bad script" --script "$tmp/bad.txt"
printf 'set nonsense 1\n' >"$tmp/bad.txt"
expect2 "bad script option" --script "$tmp/bad.txt"
expect2 "unwritable screenshot" --screenshot /proc/nope/shot.png --test-frames 1
expect2 "screenshot not png" --screenshot "$tmp/x.jpg" --test-frames 1

# --version: the version and commit, then the renderer (exit 3 without a GL
# context); --help lists the options the script's `set` takes.
"$view" --version >"$tmp/ver.out" 2>&1; rc=$?
{ [ $rc -eq 0 ] || [ $rc -eq 3 ]; } && grep -Eq '^dirt-view [0-9]+\.[0-9]+\.[0-9]+ \(commit ' "$tmp/ver.out" &&
  grep -q '^OpenGL renderer: ' "$tmp/ver.out" && ok || fail "--version: exit $rc"
"$view" --help >"$tmp/help.out" && grep -q -- '--samples-per-frame N' "$tmp/help.out" &&
  grep -q -- '--max-scene-memory SIZE' "$tmp/help.out" && ok || fail "--help"

# 6. doc/viewer.md lists every binding the program has.
missing=0
while IFS= read -r line; do
  key=$(printf '%s' "$line" | sed 's/  .*//')
  grep -qF "| $key |" "$doc" || { echo "doc/viewer.md lacks binding '$key'" >&2; missing=1; }
done < <("$view" --bindings)
[ $missing = 0 ] && ok || fail "doc/viewer.md does not list every binding"

echo "test_view: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
