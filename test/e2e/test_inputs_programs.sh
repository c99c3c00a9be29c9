#!/usr/bin/env bash
# Issue 23 in dirt-view and dirt-compare: their outputs never destroy their
# inputs (COLLISION: dirt-view's --screenshot, --report, --save-image and
# the script's screenshots against the scene, its files, --env and the
# script; dirt-compare's DIR against its scenes and presets), special files
# exit 2 at once (a FIFO as --script, --preset, scene), scenes stay in
# their folder (OUTSIDE), --strict and --max-scene-memory. Every case fails
# before a window or context is made: no display is needed.
#   test_inputs_programs.sh PATH/TO/dirt-view PATH/TO/dirt-compare
set -u
view=$(realpath "$1") compare=$(realpath "$2")
tmp=$(mktemp -d /tmp/dirt-inputs2-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# expect PROG RC ID DESCRIPTION -- ARGS...: exit status RC and, for 2, the
# last line naming PROG and the error id ID.
expect() {
  local prog=$1 want=$2 id=$3 what=$4; shift 5
  local name; name=$(basename "$prog")
  timeout 60 "$prog" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  if [ "$rc" -ne "$want" ]; then
    fail "$what: exit $rc, want $want"; tail -3 "$tmp/stderr" >&2; return
  fi
  if [ "$want" -eq 2 ] && ! tail -n 1 "$tmp/stderr" | grep -q "^$name: .*$id"; then
    fail "$what: the last line does not name $id"; tail -3 "$tmp/stderr" >&2; return
  fi
  ok
}
unchanged() { [ "$(sha1sum <"$1")" = "$2" ] && ok || fail "$1 was changed"; }
cd "$tmp" || exit 1
printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x01\x00\x02\x00\x00\x00' >tri.bin
mkgltf() {
  local name=$1 buf=${2:-tri.bin} img=${3:-} mat='' matref=''
  if [ -n "$img" ]; then
    mat=",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"$img\"}]"
    matref=',"material":0'
  fi
  cat >"$name" <<JSON
{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1$matref}]}],
 "buffers":[{"byteLength":44,"uri":"$buf"}],
 "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]$mat}
JSON
}
mkgltf scene.gltf
cp scene.gltf s.png; sum=$(sha1sum <s.png)
cp scene.gltf s.json
mkfifo fifo.txt fifo.gltf

# dirt-view
expect "$view" 2 COLLISION "--screenshot is the scene" -- s.png --screenshot s.png --test-frames 1
unchanged s.png "$sum"
expect "$view" 2 COLLISION "--report is the scene" -- s.json --report s.json --test-frames 1
expect "$view" 2 COLLISION "--save-image's PNG is the scene" -- s.png --save-image s.exr --test-frames 1
printf 'wait-frames 1\nscreenshot s.png\nquit\n' >shot.txt
expect "$view" 2 COLLISION "a script's screenshot is the scene" -- s.png --script shot.txt
unchanged s.png "$sum"
cp shot.txt script.png
expect "$view" 2 COLLISION "--screenshot is the script" -- scene.gltf --script script.png --screenshot script.png
expect "$view" 2 NOT_REGULAR "a FIFO as --script" -- scene.gltf --script fifo.txt
expect "$view" 2 NOT_REGULAR "a FIFO as the scene" -- fifo.gltf --test-frames 1
mkdir -p inner; mkgltf inner/up.gltf ../tri.bin
expect "$view" 2 OUTSIDE "a buffer outside the folder" -- inner/up.gltf --test-frames 1
mkgltf notex.gltf tri.bin missing.png
expect "$view" 2 STRICT "--strict with a missing texture" -- notex.gltf --strict --test-frames 1
python3 -c 'open("extras.gltf", "w").write("{\"asset\":{\"version\":\"2.0\"},\"extras\":[" + ",".join(["0"] * 100000) + "]}")'
expect "$view" 2 TOO_LARGE "--max-scene-memory 16M" -- extras.gltf --max-scene-memory 16M --test-frames 1

# dirt-compare
mkdir -p cmp; cp scene.gltf tri.bin cmp/; sum=$(sha1sum <cmp/scene.gltf)
expect "$compare" 2 COLLISION "a scene inside -o DIR" -- cmp/scene.gltf -o cmp --res 16x16
unchanged cmp/scene.gltf "$sum"
mkdir -p cmp2/images; cp scene.gltf cmp2/images/
cp tri.bin cmp2/images/
expect "$compare" 2 COLLISION "a scene inside DIR/images" -- cmp2/images/scene.gltf -o cmp2 --res 16x16
mkgltf out_tex.gltf tri.bin cmp3/table.md
mkdir -p cmp3; printf 'x' >cmp3/table.md
expect "$compare" 2 COLLISION "a scene's file inside DIR" -- out_tex.gltf -o cmp3 --res 16x16
printf -- '--res 16x16\n' >preset.txt
mkdir -p cmp4; cp preset.txt cmp4/
expect "$compare" 2 COLLISION "a preset inside DIR" -- scene.gltf -o cmp4 --preset cmp4/preset.txt
expect "$compare" 2 NOT_REGULAR "a FIFO as --preset" -- scene.gltf -o cmp5 --preset fifo.txt
expect "$compare" 2 OUTSIDE "a buffer outside the folder" -- inner/up.gltf -o cmp6 --res 16x16
expect "$compare" 2 STRICT "--strict with a missing texture" -- notex.gltf -o cmp7 --strict --res 16x16
expect "$compare" 2 TOO_LARGE "--max-scene-memory 16M" -- extras.gltf -o cmp8 --max-scene-memory 16M

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
