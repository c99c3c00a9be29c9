#!/usr/bin/env bash
# dirt-view's split and difference views against every engine, in both
# directions, read from the window's pixels (a real window under Xvfb):
#  - the split shows engine A's image left of the middle line and engine
#    B's right of it, each equal to dirt-render's own image of that engine
#    (same scene, size, seed, samples) through the PNG tone map;
#  - the difference view is |luminance(A) - luminance(B)| through the heat
#    ramp over 0..--diff-range;
#  - the report names the comparison and its samples.
# Pairs: every engine on each side at least once (dirt, mmrt, embree, raster),
# the README's mmrt | embree among them.
#   test_view_compare.sh DIRT-VIEW DIRT-RENDER VIEW_CHECK
set -u
view=$1 render=$2 check=$3
tmp=$(mktemp -d /tmp/dirt-view-cmp-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"
json_field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

W=96 H=72 SPP=2 RANGE=0.05
for pair in mmrt:embree embree:dirt dirt:raster raster:mmrt; do
  a=${pair%:*} b=${pair#*:}
  out=$tmp/$a-$b
  printf 'wait-samples %d\nscreenshot %s\nreport %s\nset diff on\nwait-frames 1\nscreenshot %s\nquit\n' \
    $SPP "$out-split.png" "$out.json" "$out-diff.png" >"$tmp/s.txt"
  if ! "$view" --window ${W}x$H --scale 1 --no-ui --engine "$a" --compare "$b" --seed 5 --bounces 2 \
      --spp $SPP --diff-range $RANGE --script "$tmp/s.txt" -q >"$out.out" 2>"$out.err"; then
    fail "$a | $b: dirt-view exit $?"; cat "$out.err" >&2; continue
  fi
  grep -q 'needs texture_b\|no GPU to display' "$out.err" &&
    { fail "$a | $b: the viewer logged a display failure"; cat "$out.err" >&2; }
  [ "$(json_field "$out.json" compare)" = "$b" ] && ok || fail "$a | $b: the report's comparison"
  # The raster preview's one image is its whole result: 1 sample.
  want_a=$SPP want_b=$SPP
  [ "$a" = raster ] && want_a=1
  [ "$b" = raster ] && want_b=1
  [ "$(json_field "$out.json" samples)" = $want_a ] &&
    [ "$(json_field "$out.json" compare_samples)" = $want_b ] && ok || fail "$a | $b: samples $(json_field "$out.json" samples) / $(json_field "$out.json" compare_samples)"
  for e in "$a" "$b"; do
    [ -s "$tmp/r-$e.exr" ] || "$render" -W $W -H $H --engine "$e" --seed 5 --bounces 2 --spp $SPP -q \
      -o "$tmp/r-$e.exr" || fail "dirt-render --engine $e failed"
  done
  if "$check" split "$out-split.png" "$tmp/r-$a.exr" "$tmp/r-$b.exr"; then ok; else
    fail "$a | $b: the split is not $a's image left and $b's right"; fi
  if "$check" diff "$out-diff.png" "$tmp/r-$a.exr" "$tmp/r-$b.exr" $RANGE; then ok; else
    fail "$a | $b: the difference view is not |$a - $b| through the ramp"; fi
done

# The inspector: the cursor (real X input) over pixel (30, 40) of the
# mmrt | embree split; the report's values of every channel there, of both
# engines, are those of dirt-render's images of each, bit for bit.
printf 'wait-samples %d\nwait-file %s\nwait-frames 1\nreport %s\nquit\n' $SPP "$tmp/go" \
  "$tmp/insp.json" >"$tmp/s.txt"
"$view" --window ${W}x$H --scale 1 --no-ui --engine mmrt --compare embree --seed 5 --bounces 2 --spp $SPP \
  --script "$tmp/s.txt" -q >"$tmp/insp.out" 2>&1 &
vpid=$! wid=
wid=$(window_id)
[ -n "$wid" ] && xdotool mousemove --window "$wid" 30 40 && sleep 0.5
touch "$tmp/go"
wait "$vpid" || { fail "inspector run: exit $?"; cat "$tmp/insp.out" >&2; }
python3 - "$tmp/insp.json" "$check" "$tmp/r-mmrt.exr" "$tmp/r-embree.exr" <<'PY' && ok ||
import json, struct, subprocess, sys
rep = json.load(open(sys.argv[1]))["inspect"]
f32 = lambda x: struct.unpack("f", struct.pack("f", float(x)))[0]
bad = 0
if rep.get("pixel") != [30, 40]:
    print("inspected pixel", rep.get("pixel")); sys.exit(1)
for side, exr in (("a", sys.argv[3]), ("b", sys.argv[4])):
    vals = rep[side]
    for name, got in vals.items():
        want = subprocess.run([sys.argv[2], "pixel", exr, name, "30", "40"], capture_output=True,
                              text=True).stdout.strip()
        w = float(want) if want else float("nan")
        if got is None:  # JSON null: not finite
            ok_ = w != w or abs(w) == float("inf")
        else:
            ok_ = f32(got) == f32(w)
        if not ok_:
            print(side, name, got, "want", want); bad += 1
    if len(vals) < 8:
        print(side, "has only", sorted(vals)); bad += 1
print("inspector: %d channels of a, %d of b; %d differ" % (len(rep["a"]), len(rep["b"]), bad))
sys.exit(1 if bad else 0)
PY
  fail "the inspector's values are not dirt-render's at the pixel under the cursor"

# Labels and colour bar (drawn with the panels, which start collapsed at
# 320x240): each half of the split names its engine, inside that half; the
# difference view has a colour bar over 0..--diff-range, captioned.
printf 'wait-samples 1\nwait-frames 1\nreport %s\nset diff on\nwait-frames 1\nreport %s\nquit\n' \
  "$tmp/lab-split.json" "$tmp/lab-diff.json" >"$tmp/s.txt"
"$view" --window 320x240 --scale 1 --engine mmrt --compare embree --seed 5 --bounces 1 --spp 1 \
  --diff-range $RANGE --script "$tmp/s.txt" -q >"$tmp/lab.out" 2>&1 || { fail "labels run: exit $?"; cat "$tmp/lab.out" >&2; }
python3 - "$tmp/lab-split.json" "$tmp/lab-diff.json" $RANGE <<'PY' && ok || fail "the split's labels or the difference's colour bar"
import json, sys
s, d, rng = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), float(sys.argv[3])
lab = [(l["text"], l["rect"]) for l in s.get("labels", [])]
print("split labels", lab)
bad = len(lab) != 2 or lab[0][0] != "mmrt" or lab[1][0] != "embree"
bad = bad or not (0 <= lab[0][1][0] and lab[0][1][0] + lab[0][1][2] <= 160)
bad = bad or not (160 <= lab[1][1][0] and lab[1][1][0] + lab[1][1][2] <= 320)
bad = bad or "colour_bar" in s
bar = d.get("colour_bar")
print("diff bar", bar, [l["text"] for l in d.get("labels", [])])
bad = bad or not bar or bar["lo"] != 0 or abs(bar["hi"] - rng) > 1e-6
texts = [l["text"] for l in d.get("labels", [])]
bad = bad or "|lum(mmrt) - lum(embree)|" not in texts or "0" not in texts or "%.4g" % rng not in texts
sys.exit(1 if bad else 0)
PY

echo "test_view_compare: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
