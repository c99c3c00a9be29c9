#!/usr/bin/env bash
# dirt-view's inspector, read from a real window under Xvfb with real X
# input from xdotool:
#  - pass times: after several frames the report's build passes (dirt) show
#    the times of the one build, the same numbers as after the first sample
#    (not 0; one pass too short for the clock may read 0 in both), and the
#    path tracer's passes have times too;
#  - memory: at the top of the Numbers panel, inside the panel and the
#    window (not below the fold), with the session's bytes;
#  - zoom: Ctrl + wheel over window pixel (40, 30) of a 1:1 render zooms to
#    2x about it: the window shows dirt-render's image with each pixel a
#    2x2 block, the block under the cursor the same render pixel; the
#    inspector names the render pixel under the cursor; Z goes back to
#    fitted; the script's zoom 4 and pan-image place the image where they
#    say;
#  - colour bars: the difference view's bar and a heat-map buffer's (depth)
#    are the present shader's ramp, column by column, in the screenshot;
#  - --compare-image: the split and difference against an EXR from disk,
#    the inspector's reference values, and its up-front refusals;
#  - shader reload (F5) from DIRT_GLSL_DIR, and a broken shader kept out;
#    from the source tree when run from the build tree; unavailable to a
#    copy outside it (as installed).
#   test_view_inspect.sh DIRT-VIEW DIRT-RENDER VIEW_CHECK
set -u
view=$1 render=$2 check=$3
tmp=$(mktemp -d /tmp/dirt-view-insp-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"

# ---- pass times and memory ----
# 4 frames of 1 sample each; the report after the last one.
printf 'wait-samples 1\nreport %s\nwait-samples 4\nwait-frames 1\nreport %s\nquit\n' \
  "$tmp/passes1.json" "$tmp/passes.json" >"$tmp/s.txt"
"$view" --window 1024x768 -W 64 -H 48 --spp 4 --seed 5 --bounces 2 --script "$tmp/s.txt" -q \
  >"$tmp/passes.out" 2>&1 || { fail "passes run: exit $?"; cat "$tmp/passes.out" >&2; }
python3 - "$tmp/passes1.json" "$tmp/passes.json" <<'PY' && ok || fail "the build passes' times after several frames"
import json, sys
r1 = json.load(open(sys.argv[1]))
r = json.load(open(sys.argv[2]))
build1 = [p for p in r1["passes"] if p["build"]]
build = [p for p in r["passes"] if p["build"]]
pt = [p for p in r["passes"] if not p["build"]]
print("frames %d, samples %d; build passes: %s; path tracer: %s" % (r["frames"], r["samples"],
      ", ".join("%s %.3f" % (p["name"], p["ms"]) for p in build),
      ", ".join("%s %.3f" % (p["name"], p["ms"]) for p in pt)))
print("after the first sample (frame %d): %s" % (r1["frames"],
      ", ".join("%s %.3f" % (p["name"], p["ms"]) for p in build1)))
# The build ran once, before the first sample: every later frame shows
# that build's times, the same numbers (a pass too short for the clock may
# read 0 in both), not 0 for all.
bad = r["frames"] < 4 or r["samples"] != 4 or len(build) < 3 or len(pt) < 3
bad = bad or [(p["name"], p["ms"]) for p in build] != [(p["name"], p["ms"]) for p in build1]
bad = bad or sum(1 for p in build if p["ms"] > 0) < len(build) - 1
bad = bad or not any(p["ms"] > 0 for p in pt)
sys.exit(1 if bad else 0)
PY
python3 - "$tmp/passes.json" <<'PY' && ok || fail "memory is not in view at the top of the Numbers panel"
import json, sys
r = json.load(open(sys.argv[1]))
m = r["memory"]
x, y, w, h = m["rect"]
win_w, win_h = r["window"]
numbers = [p for p in r["panels"] if p[0] > 340]  # Settings is at x = 8
print("memory", m, "numbers panel", numbers, "window", r["window"])
bad = not numbers or w <= 0 or h <= 0 or m["used"] <= 0 or m["allocated"] < m["used"]
if not bad:
    px, py, pw, ph = numbers[0]
    # inside the panel, in its first lines, and inside the window
    bad = not (px <= x and x + w <= px + pw and py <= y and y + h <= py + ph)
    bad = bad or y - py > 60 or y + h > win_h
sys.exit(1 if bad else 0)
PY

# ---- zoom, pan and the inspector's readout ----
W=160 H=120
"$render" -W $W -H $H --seed 5 --bounces 2 --spp 2 -q --png -o "$tmp/r.exr" || fail "dirt-render failed"
cat >"$tmp/s.txt" <<EOF
wait-samples 2
wait-frames 1
screenshot $tmp/z1.png
wait-file $tmp/go1
wait-frames 1
screenshot $tmp/z2.png
report $tmp/z2.json
wait-file $tmp/go2
wait-frames 1
report $tmp/z2b.json
wait-file $tmp/go3
wait-frames 1
report $tmp/fit.json
zoom 4 80 60
wait-frames 1
screenshot $tmp/z4.png
report $tmp/z4.json
pan-image 12 -8
wait-frames 1
screenshot $tmp/z4p.png
report $tmp/z4p.json
quit
EOF
"$view" --window ${W}x$H --no-ui --seed 5 --bounces 2 --spp 2 --script "$tmp/s.txt" -q \
  >"$tmp/zoom.out" 2>&1 &
vpid=$!
wid=$(window_id)
[ -n "$wid" ] || fail "no dirt-view window"
for _ in $(seq 600); do [ -s "$tmp/z1.png" ] && break; sleep 0.1; done
# Ctrl + one wheel step up over window pixel (40, 30).
xdotool mousemove --window "$wid" 40 30; sleep 0.3
xdotool keydown ctrl; sleep 0.2; xdotool click 4; sleep 0.2; xdotool keyup ctrl; sleep 0.3
touch "$tmp/go1"
for _ in $(seq 100); do [ -s "$tmp/z2.json" ] && break; sleep 0.1; done
# The cursor over window pixel (101, 71): render pixel ((101 + 40) / 2, (71 + 30) / 2).
xdotool mousemove --window "$wid" 101 71; sleep 0.3
touch "$tmp/go2"
for _ in $(seq 100); do [ -s "$tmp/z2b.json" ] && break; sleep 0.1; done
xdotool key z; sleep 0.3
touch "$tmp/go3"
wait "$vpid" || { fail "zoom run: exit $?"; cat "$tmp/zoom.out" >&2; }
# 1:1 first: the window is the render.
if "$check" zoom "$tmp/z1.png" "$tmp/r.png" 0 0 1; then ok; else fail "1:1: the window is not the render"; fi
# 2x about (40, 30): the image's top left at (40 - 2 * 40, 30 - 2 * 30).
if "$check" zoom "$tmp/z2.png" "$tmp/r.png" -40 -30 2; then ok; else
  fail "Ctrl + wheel: the window is not the render at 2x about the cursor"; fi
python3 - "$tmp" "$check" <<'PY' && ok || fail "the reports of the zoom, or the inspector's pixel under the cursor"
import json, subprocess, sys
t = sys.argv[1]
z2, z2b, fit = (json.load(open("%s/%s.json" % (t, n))) for n in ("z2", "z2b", "fit"))
z4, z4p = (json.load(open("%s/%s.json" % (t, n))) for n in ("z4", "z4p"))
print("z2", z2["zoom"], z2["image_rect"], z2["inspect"].get("pixel"))
print("z2b", z2b["zoom"], z2b["inspect"].get("pixel"), "fit", fit["zoom"], fit["image_rect"],
      fit["inspect"].get("pixel"))
print("z4", z4["zoom"], z4["image_rect"], "after pan", z4p["image_rect"])
bad = z2["zoom"] != 2 or z2["image_rect"] != [-40, -30, 320, 240]
bad |= z2["inspect"].get("pixel") != [40, 30]            # the point under the cursor stayed
bad |= z2b["inspect"].get("pixel") != [70, 50]           # (101 + 40) // 2, (71 + 30) // 2
# the inspector's R there is the render's R at that pixel
want = subprocess.run([sys.argv[2], "pixel", t + "/r.exr", "R", "70", "50"], capture_output=True,
                      text=True).stdout.strip()
print("R at 70, 50:", z2b["inspect"].get("a", {}).get("R"), "want", want)
bad |= abs(z2b["inspect"]["a"]["R"] - float(want)) > 1e-6 * max(1, abs(float(want)))
bad |= fit["zoom"] != 0 or fit["image_rect"] != [0, 0, 160, 120]
bad |= fit["inspect"].get("pixel") != [101, 71]
# zoom 4 about (80, 60) from fitted: the render's centre stays at the window's
bad |= z4["zoom"] != 4 or z4["image_rect"] != [-240, -180, 640, 480]
bad |= z4p["image_rect"] != [-240 + 12, -180 - 8, 640, 480]
sys.exit(1 if bad else 0)
PY
if "$check" zoom "$tmp/z4p.png" "$tmp/r.png" -228 -188 4; then ok; else
  fail "zoom 4 and pan-image: the window is not the render at 4x, moved"; fi

# ---- colour bars ----
# At 320x240 the panels start collapsed; the bar is drawn over the image.
printf 'wait-samples 1\nset diff on\nwait-frames 1\nscreenshot %s\nreport %s\nset diff off\nset compare none\nset buffer depth\nwait-frames 2\nscreenshot %s\nreport %s\nquit\n' \
  "$tmp/bar-diff.png" "$tmp/bar-diff.json" "$tmp/bar-depth.png" "$tmp/bar-depth.json" >"$tmp/s.txt"
"$view" --window 320x240 --engine mmrt --compare embree --seed 5 --bounces 1 --spp 1 \
  --diff-range 0.05 --script "$tmp/s.txt" -q >"$tmp/bar.out" 2>&1 || { fail "bars run: exit $?"; cat "$tmp/bar.out" >&2; }
for what in diff depth; do
  rect=$(python3 -c "import json,sys; b=json.load(open(sys.argv[1])).get('colour_bar'); print(*[int(v) for v in b['rect']] if b else '')" "$tmp/bar-$what.json")
  # shellcheck disable=SC2086
  if [ -n "$rect" ] && "$check" ramp "$tmp/bar-$what.png" $rect; then ok; else
    fail "the $what view's colour bar is not the display ramp (bar: ${rect:-none})"; fi
done

# ---- a reference image from disk ----
# Embree's image (another seed) as the reference, dirt's render beside it: left of the
# line dirt-render's dirt image, right of it the EXR; the difference is the
# ramp of |lum(dirt) - lum(EXR)|; the inspector's right-hand values over
# pixel (70, 40) are the EXR's there. The render takes the EXR's size.
W=96 H=72
"$render" -W $W -H $H --engine embree --seed 9 --bounces 2 --spp 2 -q -o "$tmp/ref.exr" || fail "dirt-render embree"
"$render" -W $W -H $H --engine dirt --seed 5 --bounces 2 --spp 2 -q -o "$tmp/dirt.exr" || fail "dirt-render dirt"
cat >"$tmp/s.txt" <<EOF
wait-samples 2
wait-frames 1
screenshot $tmp/ref-split.png
set diff on
wait-frames 1
screenshot $tmp/ref-diff.png
wait-file $tmp/go4
wait-frames 1
report $tmp/ref.json
quit
EOF
"$view" --window ${W}x$H --no-ui --seed 5 --bounces 2 --spp 2 --diff-range 0.05 \
  --compare-image "$tmp/ref.exr" --script "$tmp/s.txt" -q >"$tmp/ref.out" 2>&1 &
vpid=$!
wid=$(window_id)
[ -n "$wid" ] && xdotool mousemove --window "$wid" 70 40 && sleep 0.3
touch "$tmp/go4"
wait "$vpid" || { fail "reference run: exit $?"; cat "$tmp/ref.out" >&2; }
if "$check" split "$tmp/ref-split.png" "$tmp/dirt.exr" "$tmp/ref.exr"; then ok; else
  fail "--compare-image: the split is not dirt's image left and the EXR right"; fi
if "$check" diff "$tmp/ref-diff.png" "$tmp/dirt.exr" "$tmp/ref.exr" 0.05; then ok; else
  fail "--compare-image: the difference is not |dirt - EXR| through the ramp"; fi
python3 - "$tmp/ref.json" "$check" "$tmp/ref.exr" <<'PY' && ok || fail "--compare-image: the report or the inspector's reference values"
import json, struct, subprocess, sys
r = json.load(open(sys.argv[1]))
f32 = lambda x: struct.unpack("f", struct.pack("f", float(x)))[0]
insp = r["inspect"]
print("compare", r["compare"], r.get("compare_image"), "render", r["render"], "pixel", insp.get("pixel"))
bad = r["compare"] != "reference" or r["render"] != [96, 72] or insp.get("pixel") != [70, 40]
b = insp.get("b", {})
for name in ("R", "G", "B", "A", "albedo.R", "N.X", "Z", "ID"):
    want = subprocess.run([sys.argv[2], "pixel", sys.argv[3], name, "70", "40"],
                          capture_output=True, text=True).stdout.strip()
    got = b.get(name)
    same = got is not None and want and f32(got) == f32(float(want))
    if not same:
        print(name, got, "want", want); bad = True
sys.exit(1 if bad else 0)
PY
# Refused up front (exit 2, no window, nothing written, the reference
# untouched): missing, not an .exr name, not an EXR, a size that is not the
# render's, the reference as an output (of the command line or a script).
sum_before=$(md5sum <"$tmp/ref.exr")
printf 'not an exr\n' >"$tmp/bad.exr"
printf 'save-image %s\nquit\n' "$tmp/ref.exr" >"$tmp/clobber.txt"
i=0
for args in "--compare-image $tmp/missing.exr" "--compare-image $tmp/ref.png" \
    "--compare-image $tmp/bad.exr" "--compare-image $tmp/ref.exr -W 64 -H 48" \
    "--compare-image $tmp/ref.exr --save-image $tmp/ref.exr" \
    "--compare-image $tmp/ref.exr --script $tmp/clobber.txt"; do
  i=$((i + 1))
  # shellcheck disable=SC2086
  "$view" --window 96x72 --no-ui --test-frames 1 $args -q >"$tmp/bad$i.out" 2>&1
  rc=$?
  if [ $rc -eq 2 ] && grep -q 'compare-image' "$tmp/bad$i.out"; then ok; else
    fail "dirt-view $args: exit $rc (want 2 naming --compare-image)"; cat "$tmp/bad$i.out" >&2; fi
done
[ "$(md5sum <"$tmp/ref.exr")" = "$sum_before" ] && ok || fail "the reference was overwritten"

# ---- shader reload (F5) ----
# The shaders read from a copy of the source tree (DIRT_GLSL_DIR). The
# present shader edited to show 255 - q, a real F5: the window is the
# negative of what it was, exactly. Then a path tracer shader that does not
# compile, F5: the compiler's error in the log, the old programs kept (the
# same window, the reload count unchanged); then a broken present shader,
# F5: the same.
glsl_src=$(dirname "$0")/../../glsl
cp -r "$glsl_src" "$tmp/glsl"
cat >"$tmp/s.txt" <<EOF
wait-samples 1
wait-frames 1
screenshot $tmp/sh-a.png
wait-file $tmp/go5
wait-frames 2
screenshot $tmp/sh-b.png
report $tmp/sh-b.json
wait-file $tmp/go6
wait-frames 2
screenshot $tmp/sh-c.png
report $tmp/sh-c.json
wait-file $tmp/go7
wait-frames 2
screenshot $tmp/sh-d.png
report $tmp/sh-d.json
quit
EOF
DIRT_GLSL_DIR=$tmp/glsl "$view" --window 96x72 --no-ui --seed 5 --bounces 2 --spp 1 \
  --script "$tmp/s.txt" >"$tmp/sh.out" 2>&1 &
vpid=$!
wid=$(window_id)
[ -n "$wid" ] && xdotool mousemove --window "$wid" 10 10
for _ in $(seq 600); do [ -s "$tmp/sh-a.png" ] && break; sleep 0.1; done
sed -i 's/out_color = vec4(rgb, 1.0);/out_color = vec4(vec3(1.0) - rgb, 1.0);/' "$tmp/glsl/present/present.frag"
xdotool key F5; sleep 0.5; touch "$tmp/go5"
for _ in $(seq 600); do [ -s "$tmp/sh-b.json" ] && break; sleep 0.1; done
sed -i '1a this is not GLSL;' "$tmp/glsl/integrator/raygen.comp"
xdotool key F5; sleep 0.5; touch "$tmp/go6"
for _ in $(seq 600); do [ -s "$tmp/sh-c.json" ] && break; sleep 0.1; done
cp "$glsl_src/integrator/raygen.comp" "$tmp/glsl/integrator/raygen.comp"
sed -i '1a this is not GLSL either;' "$tmp/glsl/present/present.frag"
xdotool key F5; sleep 0.5; touch "$tmp/go7"
wait "$vpid" || { fail "shader reload run: exit $?"; cat "$tmp/sh.out" >&2; }
"$check" pngs "$tmp/sh-a.png" "$tmp/sh-b.png" negative && ok || fail "F5 after editing present.frag: the window is not the negative"
"$check" pngs "$tmp/sh-b.png" "$tmp/sh-c.png" same && "$check" pngs "$tmp/sh-b.png" "$tmp/sh-d.png" same &&
  ok || fail "F5 with a broken shader changed the window (the old programs were not kept)"
python3 - "$tmp" <<'PY' && ok || fail "the reports' reload count or status"
import json, sys
rb, rc, rd = (json.load(open("%s/sh-%s.json" % (sys.argv[1], k))) for k in "bcd")
print("reloads", rb["shader_reloads"], rc["shader_reloads"], rd["shader_reloads"])
print("failures", rb["shader_reload_failures"], rc["shader_reload_failures"], rd["shader_reload_failures"])
st = [r["shader_reload_status"] for r in (rb, rc, rd)]
print("statuses:", " | ".join(st))
bad = rb["shader_reloads"] != 1 or rc["shader_reloads"] != 1 or rd["shader_reloads"] != 1
bad |= [r["shader_reload_failures"] for r in (rb, rc, rd)] != [0, 1, 2]
bad |= "reloaded" not in st[0] or "failed" not in st[1] or "failed" not in st[2]
sys.exit(1 if bad else 0)
PY
grep -q 'raygen' "$tmp/sh.out" && grep -q 'present' "$tmp/sh.out" && ok ||
  { fail "the compiler's errors of the broken shaders are not in the log"; cat "$tmp/sh.out" >&2; }
# Without DIRT_GLSL_DIR, the build's dirt-view (run from its build tree)
# reads the source tree's glsl/ on F5: the report names that folder, and a
# real F5 reloads from it (the source tree is only read: the window stays
# the same). A copy of the program outside the build tree (as installed)
# keeps the embedded shaders and F5 says it is unavailable.
cat >"$tmp/s.txt" <<EOF
wait-samples 1
wait-frames 1
screenshot $tmp/sh-f.png
report $tmp/sh-f.json
wait-file $tmp/go8
wait-frames 2
screenshot $tmp/sh-g.png
report $tmp/sh-g.json
quit
EOF
env -u DIRT_GLSL_DIR "$view" --window 96x72 --no-ui --seed 5 --bounces 2 --spp 1 \
  --script "$tmp/s.txt" >"$tmp/shf.out" 2>&1 &
vpid=$!
wid=$(window_id)
[ -n "$wid" ] && xdotool mousemove --window "$wid" 10 10
for _ in $(seq 600); do [ -s "$tmp/sh-f.json" ] && break; sleep 0.1; done
xdotool key F5; sleep 0.5; touch "$tmp/go8"
wait "$vpid" || { fail "build tree run: exit $?"; cat "$tmp/shf.out" >&2; }
python3 - "$tmp" "$(cd "$glsl_src" && pwd -P)" <<'PY' && ok || fail "run from the build tree, F5 does not read the source tree's glsl/"
import json, os, sys
rf, rg = (json.load(open("%s/sh-%s.json" % (sys.argv[1], k))) for k in "fg")
print("before F5:", rf["shader_source"], rf["shader_source_dir"], "| after:", rg["shader_reloads"],
      rg["shader_reload_status"])
bad = rf["shader_source"] != "build tree" or os.path.realpath(rf["shader_source_dir"]) != sys.argv[2]
bad |= rg["shader_reloads"] != 1 or rf["shader_source_dir"] not in rg["shader_reload_status"]
sys.exit(1 if bad else 0)
PY
"$check" pngs "$tmp/sh-f.png" "$tmp/sh-g.png" same && ok || fail "F5 from the source tree changed the window"
mkdir -p "$tmp/bin"
cp "$view" "$tmp/bin/dirt-view"
printf 'wait-samples 1\nkey F5\nwait-frames 1\nreport %s\nquit\n' "$tmp/sh-e.json" >"$tmp/s.txt"
env -u DIRT_GLSL_DIR "$tmp/bin/dirt-view" --window 96x72 --no-ui --spp 1 --script "$tmp/s.txt" -q \
  >"$tmp/she.out" 2>&1 || fail "embedded shaders run: exit $?"
python3 -c "import json,sys; r=json.load(open(sys.argv[1])); s=r['shader_reload_status']; print(s); sys.exit(0 if 'unavailable: this dirt-view is not run from a meson build tree' in s and r['shader_reloads'] == 0 and r['shader_source'] == 'embedded' else 1)" \
  "$tmp/sh-e.json" && ok || fail "F5 with embedded shaders does not say it is unavailable"

echo "test_view_inspect: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
