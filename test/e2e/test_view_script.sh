#!/usr/bin/env bash
# dirt-view's scripted mode (a real window under Xvfb):
#  - every key binding acts from the script's `key NAME` as from the
#    keyboard: after each, the report (or a file it writes) shows its effect;
#  - the example script data/view-tour.txt runs and writes what it says;
#  - a script output path that cannot be written exits 2 before the window
#    (nothing written), not when the line is reached.
#   test_view_script.sh DIRT-VIEW DATA-DIR
set -u
view=$1 data=$2
tmp=$(mktemp -d /tmp/dirt-view-script-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"
view=$(cd "$(dirname "$view")" && pwd)/$(basename "$view")
data=$(cd "$data" && pwd)

# 1. Every key binding from the script: KEY, then a report k-N.json.
#    (expect N FIELD VALUE: the report's field after key N.)
keys=(F1 H H 2 9 1 Tab V X Space Right Left Minus Equal W R C P O)
{
  echo 'wait-samples 1'
  i=0
  for k in "${keys[@]}"; do
    i=$((i + 1))
    echo "key $k"
    echo 'wait-frames 1'
    echo "report k-$i.json"
  done
  echo 'key Escape'
  echo 'wait-frames 2'
  echo 'report after-escape.json'
  echo 'quit'
} >"$tmp/keys.txt"
mkdir "$tmp/run"
if (cd "$tmp/run" && "$view" --window 200x150 --scale 1 --spp 1 --script "$tmp/keys.txt" -q \
    >"$tmp/keys.out" 2>"$tmp/keys.err"); then ok; else
  fail "keys run: exit $?"; cat "$tmp/keys.err" >&2; fi
field() { python3 -c "import json,sys; v=json.load(open(sys.argv[1]))[sys.argv[2]]; print(str(v).lower() if isinstance(v, bool) else v)" "$tmp/run/k-$1.json" "$2" 2>/dev/null; }
expect() {
  local n=$1 f=$2 want=$3 got
  got=$(field "$n" "$f")
  [ "$got" = "$want" ] && ok || fail "after key ${keys[$((n - 1))]}: $f is '$got', want '$want'"
}
expect 1 help_shown true
expect 2 panels_shown false
expect 3 panels_shown true
expect 4 buffer albedo
expect 5 buffer zmax
expect 6 buffer beauty
expect 7 engine mmrt
expect 8 compare dirt
expect 9 diff true
expect 10 play true
expect 11 play false
# Space plays (the time moves), Right stops and steps 1/24 s, Left steps back.
python3 -c "
import json, sys
t = [json.load(open(sys.argv[1] + '/k-%d.json' % i))['time'] for i in (10, 11, 12)]
sys.exit(0 if abs(t[1] - t[0] - 1 / 24) < 1e-9 and abs(t[2] - t[0]) < 1e-9 else 1)" "$tmp/run" &&
  ok || fail "keys Right, Left: times $(field 10 time), $(field 11 time), $(field 12 time)"
expect 13 exposure -1
expect 14 exposure 0
expect 15 camera_mode look
expect 16 camera_mode default
expect 17 camera_mode scene
[ -s "$tmp/run/dirt-view-1.png" ] && ok || fail "key P wrote no dirt-view-1.png"
[ -s "$tmp/run/dirt-view-2.exr" ] && [ -s "$tmp/run/dirt-view-2.png" ] && ok ||
  fail "key O wrote no dirt-view-2.exr and .png"
[ ! -e "$tmp/run/after-escape.json" ] && ok || fail "key Escape did not quit"

# 2. The example script, run where its files go.
mkdir "$tmp/tour"
if (cd "$tmp/tour" && "$view" --window 160x120 --scale 1 --seed 2 --script "$data/view-tour.txt" -q \
    >"$tmp/tour.out" 2>"$tmp/tour.err"); then ok; else
  fail "data/view-tour.txt: exit $?"; cat "$tmp/tour.err" >&2; fi
for f in beauty help albedo split diff; do
  [ -s "$tmp/tour/view-tour-$f.png" ] && ok || fail "the tour wrote no view-tour-$f.png"
done
[ "$(python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(r['compare'], r['diff'], r['camera_mode'])" \
  "$tmp/tour/view-tour.json" 2>/dev/null)" = "embree True look" ] && ok ||
  fail "the tour's report: not the difference against embree from the free camera"
for f in help albedo split diff; do
  cmp -s "$tmp/tour/view-tour-beauty.png" "$tmp/tour/view-tour-$f.png" &&
    fail "the tour's $f screenshot is the beauty one" || ok
done

# 3. Script outputs that cannot be written exit 2 up front, nothing written.
for line in 'screenshot /proc/nope/s.png' 'save-image /proc/nope/s.exr' 'report /proc/nope/r.json'; do
  printf 'wait-samples 1\nsave-image %s\n%s\nquit\n' "$tmp/early.exr" "$line" >"$tmp/bad.txt"
  "$view" --window 96x72 --script "$tmp/bad.txt" -q >"$tmp/bad.out" 2>"$tmp/bad.err"
  rc=$?
  if [ $rc -eq 2 ] && grep -q 'script line 3' "$tmp/bad.err" && [ ! -e "$tmp/early.exr" ]; then ok; else
    fail "'$line': exit $rc (want 2 before the window, nothing written)"; cat "$tmp/bad.err" >&2; fi
done

echo "test_view_script: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
