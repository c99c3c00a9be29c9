#!/usr/bin/env bash
# A scene dropped on dirt-view's window, as a file manager drops it (XDND,
# from xdnd_drop) in a real window under Xvfb:
#  - a scene one of whose files this run will write (the script's screenshot
#    is named like its texture) is refused: the shown scene stays, the log
#    says COLLISION, and the texture is untouched when the refusal is made;
#  - the same scene from another folder opens, and the viewer's saved image
#    of it equals dirt-render's with the viewer's own render_args;
#  - the P key never replaces a file: with dirt-view-1.png present, it
#    writes dirt-view-2.png.
#   test_view_drop.sh DIRT-VIEW DIRT-RENDER VIEW-CHECK XDND-DROP
#   test_view_drop.sh --no-x11   (the build found no Xlib: skip, or fail in CI)
set -u
if [ "${1:-}" = --no-x11 ]; then
  [ "${CI:-}" = true ] && { echo "CI=true: Xlib (libx11-dev) missing is a failure"; exit 1; }
  echo "Xlib missing: skipping"; exit 77
fi
view=$1 render=$2 check=$3 drop=$4
tmp=$(mktemp -d /tmp/dirt-view-drop-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
truck=${DIRT_SHARED_DIR:-}/scenes/gltf/CesiumMilkTruck
if [ ! -f "$truck/CesiumMilkTruck.gltf" ]; then
  [ "${CI:-}" = true ] && { echo "CI=true but the shared scene $truck is missing"; exit 1; }
  echo "shared scenes absent: skipping"; exit 77
fi
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"
json_field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }

mkdir -p "$tmp/a" "$tmp/b" "$tmp/cwd"
cp "$truck"/CesiumMilkTruck.gltf "$truck"/CesiumMilkTruck.png "$truck"/CesiumMilkTruck0.bin "$tmp/a/"
cp "$truck"/CesiumMilkTruck.gltf "$truck"/CesiumMilkTruck.png "$truck"/CesiumMilkTruck0.bin "$tmp/b/"
want_tex=$(md5sum <"$tmp/a/CesiumMilkTruck.png")
echo keep >"$tmp/cwd/dirt-view-1.png"

cat >"$tmp/s.txt" <<EOF
wait-file $tmp/go1
wait-frames 2
report $tmp/r1.json
wait-file $tmp/go2
wait-frames 2
wait-samples 1
report $tmp/r2.json
save-image $tmp/b.exr
key P
wait-frames 2
screenshot $tmp/a/CesiumMilkTruck.png
quit
EOF
(cd "$tmp/cwd" && exec "$view" --window 160x120 --no-ui --spp 1 --scale 1 --script "$tmp/s.txt") \
  >"$tmp/view.out" 2>&1 &
vpid=$! wid=
wid=$(window_id)
if [ -z "$wid" ]; then
  fail "no window"; touch "$tmp/go1" "$tmp/go2"
else
  "$drop" "$wid" "$tmp/a/CesiumMilkTruck.gltf" || fail "the first drop was not delivered"
  [ "$(md5sum <"$tmp/a/CesiumMilkTruck.png")" = "$want_tex" ] && ok ||
    fail "the refused scene's texture changed"
  touch "$tmp/go1"
  for _ in $(seq 300); do [ -f "$tmp/r1.json" ] && break; sleep 0.1; done
  "$drop" "$wid" "$tmp/b/CesiumMilkTruck.gltf" || fail "the second drop was not delivered"
  touch "$tmp/go2"
fi
wait "$vpid" || fail "dirt-view exited $?"

# The refusal: the shown scene stayed, and the log says why.
scene1=$(json_field "$tmp/r1.json" scene 2>/dev/null)
[ "$scene1" = "default scene" ] && ok || fail "after the refused drop the scene is '$scene1', not the default scene"
grep -q "COLLISION.*CesiumMilkTruck.png" "$tmp/view.out" && ok ||
  fail "the log does not say COLLISION for the texture"
grep -q "did not open '$tmp/a/CesiumMilkTruck.gltf'" "$tmp/view.out" && ok ||
  fail "the status does not say the scene was not opened"

# The second drop opened, and shows what dirt-render makes of it.
scene2=$(json_field "$tmp/r2.json" scene 2>/dev/null)
case "$scene2" in *b/CesiumMilkTruck.gltf) ok ;; *) fail "after the second drop the scene is '$scene2'" ;; esac
args=$(json_field "$tmp/r2.json" render_args) spp=$(json_field "$tmp/r2.json" samples)
# shellcheck disable=SC2086
"$render" "$tmp/b/CesiumMilkTruck.gltf" $args --spp "$spp" -q -o "$tmp/b-r.exr" ||
  fail "dirt-render $args failed"
if "$check" same "$tmp/b.exr" "$tmp/b-r.exr"; then ok; else
  fail "the dropped scene's image is not dirt-render's"; fi

# P kept the file that was there.
[ "$(cat "$tmp/cwd/dirt-view-1.png")" = keep ] && ok || fail "P replaced dirt-view-1.png"
[ -s "$tmp/cwd/dirt-view-2.png" ] && ok || fail "P did not write dirt-view-2.png"

echo "test_view_drop: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
