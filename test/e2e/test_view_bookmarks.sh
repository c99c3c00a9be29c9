#!/usr/bin/env bash
# dirt-view's camera bookmarks, in a real window under Xvfb with real X
# input from xdotool, on a copy of data/default_scene.gltf in a temporary
# folder (the bookmarks file goes beside the scene):
#  - Ctrl + 3 saves the camera in slot 3 and writes s.gltf.bookmarks.json;
#    a drag moves the camera; Shift + 3 brings the saved camera back: the
#    window then equals dirt-render's image of the reported camera (same
#    seed and samples, pixel for pixel), and the camera is the file's;
#  - a new run reads the file: Shift + 3 gives the same camera and the same
#    window; the script's bookmark save / delete rewrite the file;
#  - a malformed file: a log line, no bookmarks, the file left untouched
#    (a bookmark saved then stays in memory); a folder the viewer cannot
#    write: the bookmark stays in memory, the status line says so;
#  - the bookmarks file as an output of the run (--report) exits 2, file
#    untouched; a bad `bookmark` script line exits 2 before the window.
#   test_view_bookmarks.sh DIRT-VIEW DIRT-RENDER VIEW_CHECK SCENE
set -u
view=$1 render=$2 check=$3 scene=$4
tmp=$(mktemp -d /tmp/dirt-view-bm-XXXXXX)
trap 'chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"

wait_for() { for _ in $(seq 600); do [ -s "$1" ] && return 0; sleep 0.1; done; return 1; }
json() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print($2)" "$3"; }

mkdir -p "$tmp/sc"
cp "$scene" "$tmp/sc/s.gltf"
bm="$tmp/sc/s.gltf.bookmarks.json"
common=(--window 160x120 --scale 1 --no-ui --seed 5 --bounces 2 --spp 2 -q)

# ---- save (Ctrl + 3), move (a drag), recall (Shift + 3) ----
cat >"$tmp/a.txt" <<EOF
wait-samples 2
wait-frames 1
report $tmp/a0.json
wait-file $tmp/go1
wait-frames 2
report $tmp/a1.json
wait-file $tmp/go2
wait-frames 1
wait-samples 2
wait-frames 1
screenshot $tmp/a2.png
report $tmp/a2.json
quit
EOF
"$view" "$tmp/sc/s.gltf" "${common[@]}" --script "$tmp/a.txt" >"$tmp/a.out" 2>&1 &
vpid=$!
wid=$(window_id)
[ -n "$wid" ] || fail "no dirt-view window"
wait_for "$tmp/a0.json" || fail "no first report"
xdotool mousemove --window "$wid" 80 60; sleep 0.3
xdotool key ctrl+3; sleep 0.5
xdotool mousedown 1; for _ in 1 2 3 4; do xdotool mousemove_relative -- 10 3; sleep 0.1; done
xdotool mouseup 1; sleep 0.5
touch "$tmp/go1"
wait_for "$tmp/a1.json" || fail "no report after the drag"
xdotool key shift+3; sleep 0.5
touch "$tmp/go2"
wait "$vpid" || { fail "the first run: exit $?"; cat "$tmp/a.out" >&2; }
python3 - "$tmp" "$bm" <<'PY' && ok || fail "Ctrl + 3 / drag / Shift + 3: the cameras or the file"
import json, sys
t, bm = sys.argv[1], sys.argv[2]
a1, a2 = (json.load(open("%s/%s.json" % (t, n))) for n in ("a1", "a2"))
f = json.load(open(bm))
print("file:", json.dumps(f)[:300])
print("after the drag:", a1["camera_args"], "| after Shift + 3:", a2["camera_args"])
marks = {b["slot"]: b for b in f["bookmarks"]}
bad = f.get("version") != 1 or sorted(marks) != [3]
bad = bad or a1["bookmarks"]["slots"] != [3] or a1["camera_args"] == a2["camera_args"]
bad = bad or a1["bookmarks"]["file"] != bm
bad = bad or marks[3]["camera_args"] != a2["camera_args"]
sys.exit(1 if bad else 0)
PY
args=$(json '' 'r["render_args"]' "$tmp/a2.json")
# shellcheck disable=SC2086
"$render" "$tmp/sc/s.gltf" $args --bounces 2 --spp 2 -q --png -o "$tmp/r.exr" ||
  fail "dirt-render of the recalled camera failed"
if "$check" zoom "$tmp/a2.png" "$tmp/r.png" 0 0 1; then ok; else
  fail "after Shift + 3 the window is not dirt-render's image of the reported camera"; fi

# ---- a new run reads the file; the script's bookmark save / delete ----
cat >"$tmp/b.txt" <<EOF
wait-samples 1
report $tmp/b0.json
wait-file $tmp/go3
wait-frames 1
wait-samples 2
wait-frames 1
screenshot $tmp/b1.png
report $tmp/b1.json
orbit 20 5
bookmark save 5
bookmark delete 3
report $tmp/b2.json
quit
EOF
"$view" "$tmp/sc/s.gltf" "${common[@]}" --script "$tmp/b.txt" >"$tmp/b.out" 2>&1 &
vpid=$!
wid=$(window_id)
wait_for "$tmp/b0.json" || fail "no report in the second run"
xdotool mousemove --window "$wid" 80 60; sleep 0.3
xdotool key shift+3; sleep 0.5
touch "$tmp/go3"
wait "$vpid" || { fail "the second run: exit $?"; cat "$tmp/b.out" >&2; }
python3 - "$tmp" "$bm" <<'PY' && ok || fail "the second run: bookmark 3 from the file, save 5, delete 3"
import json, sys
t, bm = sys.argv[1], sys.argv[2]
a2, b0, b1, b2 = (json.load(open("%s/%s.json" % (t, n))) for n in ("a2", "b0", "b1", "b2"))
f = json.load(open(bm))
print("read:", b0["bookmarks"], "camera:", b1["camera_args"], "| at exit:", json.dumps(f)[:200])
marks = {b["slot"]: b for b in f["bookmarks"]}
bad = b0["bookmarks"]["slots"] != [3] or b1["camera_args"] != a2["camera_args"]
bad = bad or b2["bookmarks"]["slots"] != [5] or sorted(marks) != [5]
bad = bad or marks[5]["camera_args"] != b2["camera_args"]
sys.exit(1 if bad else 0)
PY
if cmp -s "$tmp/a2.png" "$tmp/b1.png"; then ok; else
  fail "Shift + 3 in a new run does not show the same window"; fi

# ---- a malformed file is never overwritten ----
mkdir -p "$tmp/m"
cp "$scene" "$tmp/m/m.gltf"
printf '{"version": 1, "bookmarks": [{"slot": 12}]}\n' >"$tmp/m/m.gltf.bookmarks.json"
sum=$(md5sum <"$tmp/m/m.gltf.bookmarks.json")
printf 'wait-samples 1\nbookmark save 1\nreport %s\nquit\n' "$tmp/m.json" >"$tmp/m.txt"
"$view" "$tmp/m/m.gltf" --window 160x120 --no-ui --spp 1 --script "$tmp/m.txt" \
  >"$tmp/m.out" 2>&1 || fail "malformed file: exit $?"
if [ "$(md5sum <"$tmp/m/m.gltf.bookmarks.json")" = "$sum" ] &&
   grep -q "bookmarks '.*m.gltf.bookmarks.json' not read (INVALID" "$tmp/m.out" &&
   grep -q "bookmark 1 saved in memory only" "$tmp/m.out" &&
   [ "$(json '' 'r["bookmarks"]["slots"], r["bookmarks"]["file_kept"]' "$tmp/m.json")" = "[1] True" ]; then
  ok; else fail "a malformed bookmarks file: not said, or written over"; cat "$tmp/m.out" >&2; fi

# ---- a folder the viewer cannot write: the bookmark stays in memory ----
mkdir -p "$tmp/ro"
cp "$scene" "$tmp/ro/r.gltf"
printf 'wait-samples 1\nbookmark save 2\nreport %s\nquit\n' "$tmp/ro.json" >"$tmp/ro.txt"
chmod 0555 "$tmp/ro"
chmod 0777 "$tmp"
as=() ro_view=$view
# root writes anywhere: run the viewer as nobody there (a copy of it in
# $tmp, which nobody may read whatever the build folder's permissions).
if [ "$(id -u)" = 0 ]; then
  as=(setpriv --reuid=65534 --regid=65534 --clear-groups --)
  mkdir -p "$tmp/bin" && cp "$view" "$tmp/bin/dirt-view" && chmod 0755 "$tmp/bin" "$tmp/bin/dirt-view"
  ro_view=$tmp/bin/dirt-view
fi
"${as[@]}" "$ro_view" "$tmp/ro/r.gltf" --window 160x120 --no-ui --spp 1 --script "$tmp/ro.txt" \
  >"$tmp/ro.out" 2>&1 || fail "unwritable folder: exit $?"
if [ ! -e "$tmp/ro/r.gltf.bookmarks.json" ] &&
   grep -q "bookmark 2 saved in memory only: cannot write" "$tmp/ro.out" &&
   [ "$(json '' 'r["bookmarks"]["slots"]' "$tmp/ro.json")" = "[2]" ]; then
  ok; else fail "a folder the viewer cannot write: not said, or not kept"; cat "$tmp/ro.out" >&2; fi
chmod 0755 "$tmp/ro" "$tmp"

# ---- the bookmarks file is never an output of the run; bad script lines ----
sum=$(md5sum <"$bm")
"$view" "$tmp/sc/s.gltf" --window 160x120 --no-ui --test-frames 1 --report "$bm" \
  >"$tmp/c.out" 2>&1
rc=$?
if [ "$rc" = 2 ] && grep -q COLLISION "$tmp/c.out" && [ "$(md5sum <"$bm")" = "$sum" ]; then ok; else
  fail "--report onto the bookmarks file: exit $rc"; cat "$tmp/c.out" >&2; fi
for line in "bookmark go 10" "bookmark jump 1" "bookmark save" "key Ctrl+Nope"; do
  printf '%s\nquit\n' "$line" >"$tmp/bad.txt"
  "$view" "$tmp/sc/s.gltf" --no-ui --script "$tmp/bad.txt" >"$tmp/bad.out" 2>&1
  rc=$?
  if [ "$rc" = 2 ] && grep -q "line 1" "$tmp/bad.out"; then ok; else
    fail "script '$line': exit $rc"; cat "$tmp/bad.out" >&2; fi
done

echo "view_bookmarks: $passes passed, $fails failed"
[ "$fails" = 0 ]
