#!/usr/bin/env bash
# What users bring and what they keep (issue 23), dirt-render as a farm
# user runs it: outputs never destroy inputs (COLLISION), special files
# exit 2 at once (NOT_REGULAR), scenes stay in their folder (OUTSIDE),
# every decoder is bounded (TOO_LARGE, TRUNCATED; the peak memory of each
# attack measured), all or nothing on a full disk (a small tmpfs, made in
# a private mount namespace: root), a dead worker's claim on this host,
# and the smaller items. Every case asserts the exit status and the error
# id of the message. Renders use the CPU engine (embree) where an image is
# needed; the one GPU render (an orthographic camera) needs an OpenGL
# context.
#   test_render_inputs.sh PATH/TO/dirt-render
set -u
render=$(realpath "$1")
tmp=$(mktemp -d /tmp/dirt-inputs-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
cpu=(--engine embree -W 16 -H 12 --spp 1 -q)

# expect RC ID DESCRIPTION -- ARGS...: runs dirt-render; checks the exit
# status and, for an exit 2, that the last line names the program and the
# error id ID ("-": none asked). The peak resident memory (KB) of the run
# is left in $peak_kb.
expect() {
  local want=$1 id=$2 what=$3; shift 4
  peak_kb=$(python3 - "$tmp" "$render" "$@" <<'PY'
import resource, subprocess, sys
with open(sys.argv[1] + "/stdout", "w") as out, open(sys.argv[1] + "/stderr", "w") as err:
    r = subprocess.run(sys.argv[2:], stdout=out, stderr=err, timeout=120)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
sys.exit(r.returncode)
PY
)
  local rc=$?
  if [ "$rc" -ne "$want" ]; then
    fail "$what: exit $rc, want $want"; tail -5 "$tmp/stderr" >&2; return 1
  fi
  if [ "$want" -ne 0 ] && [ "$id" != - ] && ! tail -n 1 "$tmp/stderr" | grep -q "^dirt-render: .*$id"; then
    fail "$what: the last line does not name $id:"; tail -3 "$tmp/stderr" >&2; return 1
  fi
  ok
}
# unchanged FILE SUM: the file still has the checksum SUM.
unchanged() { [ "$(sha1sum <"$1")" = "$2" ] && ok || fail "$1 was changed"; }

# A one-triangle glTF: mkgltf NAME [BUFFER_URI] [IMAGE_URI] [EXTRA_JSON]; the
# buffer tri.bin beside it when BUFFER_URI is not given.
printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x01\x00\x02\x00\x00\x00' >"$tmp/tri.bin"
mkgltf() {
  local name=$1 buf=${2:-tri.bin} img=${3:-} extra=${4:-}
  local mat='' matref=''
  if [ -n "$img" ]; then
    mat=",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"$img\"}]"
    matref=',"material":0'
  fi
  cat >"$name" <<JSON
{"asset":{"version":"2.0"},$extra"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1$matref}]}],
 "buffers":[{"byteLength":44,"uri":"$buf"}],
 "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]$mat}
JSON
}
cd "$tmp" || exit 1
mkgltf scene.gltf
python3 - <<'PY'
import struct, zlib
def png(path, w, h, declare=None):
    raw = b"".join(b"\0" + bytes([128, 64, 32, 255] * w) for _ in range(h))
    def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    dw, dh = declare or (w, h)
    ihdr = struct.pack(">IIBBBBB", dw, dh, 8, 6, 0, 0, 0)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
png("tex.png", 4, 4)
png("huge.png", 64, 64, (16384, 16384))
PY
"$render" scene.gltf -o ref.exr "${cpu[@]}" || fail "reference render"

# ---- 1. Outputs never destroy inputs ----
sum=$(sha1sum <ref.exr)
expect 2 COLLISION "-o is the --mse-reference" -- scene.gltf -o ref.exr --mse-reference ref.exr "${cpu[@]}"
unchanged ref.exr "$sum"
cp scene.gltf s.png; sum=$(sha1sum <s.png)
expect 2 COLLISION "-o is the scene" -- s.png -o s.png "${cpu[@]}"
unchanged s.png "$sum"
expect 2 COLLISION "--png is the scene" -- s.png -o s.exr --png "${cpu[@]}"
unchanged s.png "$sum"; [ ! -e s.exr ] && ok || fail "s.exr written"
cp scene.gltf s.json; sum=$(sha1sum <s.json)
expect 2 COLLISION "--stats is the scene" -- s.json -o out.png --stats s.json "${cpu[@]}"
unchanged s.json "$sum"; [ ! -e out.png ] && ok || fail "out.png written"
cp scene.gltf s.dot; sum=$(sha1sum <s.dot)
expect 2 COLLISION "--graph-dot is the scene" -- s.dot -o out.png --graph-dot s.dot --spp 1
unchanged s.dot "$sum"
cp scene.gltf s.jsonl; sum=$(sha1sum <s.jsonl)
expect 2 COLLISION "--log is the scene" -- s.jsonl -o out.png --log s.jsonl "${cpu[@]}"
unchanged s.jsonl "$sum"
ln scene.gltf hard.png
expect 2 COLLISION "-o is a hard link of the scene" -- scene.gltf -o hard.png "${cpu[@]}"
grep -q "another name" "$tmp/stderr" && ok || fail "the hard link is not said"
ln -s ref.exr link.exr; sum=$(sha1sum <ref.exr)
expect 2 COLLISION "-o is a symbolic link to the reference" -- scene.gltf -o link.exr --mse-reference ref.exr "${cpu[@]}"
unchanged ref.exr "$sum"
mkgltf textured.gltf tri.bin tex.png; sum=$(sha1sum <tex.png)
expect 2 COLLISION "-o is the scene's texture" -- textured.gltf -o tex.png "${cpu[@]}"
unchanged tex.png "$sum"
expect 2 COLLISION "--png is the scene's buffer's neighbour texture" -- textured.gltf -o tex.exr --png "${cpu[@]}"
cp ref.exr map.exr; sum=$(sha1sum <map.exr)
expect 2 COLLISION "-o is the --env map" -- scene.gltf -o map.exr --env map.exr "${cpu[@]}"
unchanged map.exr "$sum"
cp scene.gltf f_2.png; sum=$(sha1sum <f_2.png)
expect 2 COLLISION "frame 2 of the range is the scene" -- f_2.png -o f_%d.png --frames 0:3 "${cpu[@]}"
unchanged f_2.png "$sum"; [ ! -e f_0.png ] && ok || fail "frame 0 written before the check"
mkdir -p ads; cp scene.gltf ads/ads_mine.png; cp tri.bin ads/
expect 2 COLLISION "--debug-ads writes over the scene" -- ads/ads_mine.png -o out.png --debug-ads ads
expect 2 COLLISION "-o among the --debug-ads pictures" -- scene.gltf -o ads/ads_v0_camera_lists.png --debug-ads ads
expect 0 - "distinct inputs and outputs" -- scene.gltf -o distinct.exr --png --mse-reference ref.exr --stats distinct.json "${cpu[@]}"

# ---- 2. Budgets: the issue's attacks, each with its peak memory ----
mkgltf huge_texture.gltf tri.bin huge.png
expect 2 TOO_LARGE "a 16384^2 PNG texture in a glTF" -- huge_texture.gltf -o out.png "${cpu[@]}"
echo "huge texture: peak $peak_kb KB" >&2
[ "$peak_kb" -lt 131072 ] && ok || fail "huge texture: peak $peak_kb KB (was 3.2 GB)"
python3 -c '
import sys
open("extras.gltf", "w").write("{\"asset\":{\"version\":\"2.0\"},\"extras\":[" + ",".join(["0"] * 2200000) + "]}")
open("faces.obj", "w").write("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * 2000000)
open("extras_small.gltf", "w").write("{\"asset\":{\"version\":\"2.0\"},\"extras\":[" + ",".join(["0"] * 100000) + "]}")
'
expect 2 TOO_LARGE "2.2 million numbers in extras" -- extras.gltf -o out.png "${cpu[@]}"
echo "extras: peak $peak_kb KB" >&2
[ "$peak_kb" -lt 131072 ] && ok || fail "extras: peak $peak_kb KB (about 500 MB unbounded)"
expect 2 TOO_LARGE "an OBJ of 2 million faces" -- faces.obj -o out.png "${cpu[@]}"
echo "faces: peak $peak_kb KB" >&2
[ "$peak_kb" -lt 131072 ] && ok || fail "faces: peak $peak_kb KB (about 350 MB unbounded)"
# --max-scene-memory lowers and raises the budget (100k numbers: about 50 MB).
expect 0 - "100k numbers, default budget" -- extras_small.gltf -o out.png "${cpu[@]}"
expect 2 TOO_LARGE "100k numbers, --max-scene-memory 16M" -- extras_small.gltf -o out.png --max-scene-memory 16M "${cpu[@]}"
expect 0 - "2.2 million numbers, --max-scene-memory 1G" -- extras.gltf -o out.png --max-scene-memory 1G "${cpu[@]}"
expect 2 - "--max-scene-memory not a size" -- scene.gltf -o out.png --max-scene-memory lots
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n' >lie.hdr
expect 2 TRUNCATED "a 52-byte .hdr declaring 16384x8192" -- scene.gltf -o out.png --env lie.hdr "${cpu[@]}"
echo "lying hdr: peak $peak_kb KB" >&2
[ "$peak_kb" -lt 131072 ] && ok || fail "lying hdr: peak $peak_kb KB (was 5.8 GB)"
python3 -c '
import struct
def rgbe(w, h):
    rows = b"".join(bytes([2, 2, w >> 8, w & 255]) + bytes([128 + w, 100]) * 4 for _ in range(h))
    return b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w) + rows
d = rgbe(64, 32)
open("good.hdr", "wb").write(d)
open("cut.hdr", "wb").write(d[:len(d) // 2])
'
expect 0 - "a whole .hdr" -- scene.gltf -o out.png --env good.hdr "${cpu[@]}"
expect 2 TRUNCATED "a truncated .hdr" -- scene.gltf -o out.png --env cut.hdr "${cpu[@]}"
python3 -c '
import sys
d = open("ref.exr", "rb").read()
for a, b in ((b"\0R\0", b"\0P\0"), (b"\0G\0", b"\0Q\0"), (b"\0B\0", b"\0S\0")):
    i = d.find(a, 0, 600); d = d[:i] + b + d[i + 3:]
open("nocolour.exr", "wb").write(d)
'
expect 2 NO_COLOUR "an EXR environment without R, G, B" -- scene.gltf -o out.png --env nocolour.exr "${cpu[@]}"

# ---- 3. Special files exit 2 at once ----
mkfifo fifo.gltf fifo.exr fifo.bin fifo.mtl
ln -s /dev/zero zero.gltf
expect 2 NOT_REGULAR "a FIFO as the scene" -- fifo.gltf -o out.png "${cpu[@]}"
expect 2 NOT_REGULAR "/dev/zero as the scene" -- zero.gltf -o out.png "${cpu[@]}"
expect 2 NOT_REGULAR "a directory as the scene" -- ads -o out.png "${cpu[@]}"
expect 2 NOT_REGULAR "a FIFO as --env" -- scene.gltf -o out.png --env fifo.exr "${cpu[@]}"
mkgltf fifo_buffer.gltf fifo.bin
expect 2 NOT_REGULAR "a FIFO as a buffer" -- fifo_buffer.gltf -o out.png "${cpu[@]}"
printf 'mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >fifo.obj
expect 2 NOT_REGULAR "a FIFO as an mtllib" -- fifo.obj -o out.png "${cpu[@]}"
expect 2 NOT_REGULAR "a FIFO as --mse-reference" -- scene.gltf -o out.exr --mse-reference fifo.exr "${cpu[@]}"
[ ! -e out.exr ] && ok || fail "rendered with a FIFO reference"

# ---- 4. Scenes stay in their folder ----
mkdir -p inner outside
cp tri.bin outside/secret.bin
printf 'root:SECRETPW:0:0:root:/root:/bin/bash\n' >outside/passwd
mkgltf inner/up.gltf ../outside/secret.bin
expect 2 OUTSIDE "a buffer URI with .." -- inner/up.gltf -o out.png "${cpu[@]}"
grep -q "../outside/secret.bin" "$tmp/stderr" && ok || fail "the message does not name the reference"
expect 0 - "a buffer URI with .., allowed" -- inner/up.gltf -o out.png --allow-outside-paths "${cpu[@]}"
printf 'mtllib %s/outside/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' "$tmp" >inner/abs.obj
expect 2 OUTSIDE "an absolute mtllib" -- inner/abs.obj -o out.png "${cpu[@]}"
expect 0 - "an absolute mtllib, allowed" -- inner/abs.obj -o out.png --allow-outside-paths "${cpu[@]}"
grep -q SECRET "$tmp/stderr" && fail "a file's bytes in the messages" || ok
ln -s ../outside/secret.bin inner/link.bin
mkgltf inner/link.gltf link.bin
expect 2 OUTSIDE "a symbolic link leading out" -- inner/link.gltf -o out.png "${cpu[@]}"

# ---- 5. All or nothing ----
expect 2 - "a failed run leaves no directory it made" -- nope.gltf -o made/a/b/out.png "${cpu[@]}"
[ ! -e made ] && ok || fail "made/ left behind"
expect 2 - "a failed run leaves no empty log" -- nope.gltf -o out.png --log new/run.jsonl "${cpu[@]}"
[ ! -e new/run.jsonl ] && [ ! -e new ] && ok || fail "an empty log (or its folder) left behind"
# A full disk: a private mount namespace with a small tmpfs (root).
if unshare -m true 2>/dev/null; then
  "$render" scene.gltf -o probe.exr --png -W 64 -H 48 --spp 1 --engine embree -q || fail "probe render"
  exr=$(stat -c %s probe.exr) png=$(stat -c %s probe.png)
  cat >full.sh <<SH
set -u
mkdir -p disk && mount -t tmpfs -o size=$(( (exr + 4095) / 4096 * 4096 )) tmpfs disk || exit 9
"$render" scene.gltf -o disk/x.exr --png -W 64 -H 48 --spp 1 --engine embree -q 2>disk.err
echo "exr+png rc \$?"; ls disk | tr '\n' ' '; echo
umount disk
mount -t tmpfs -o size=8k tmpfs disk || exit 9
python3 -c 'import json; open("disk/log.jsonl", "w").write(json.dumps({"pad": "x" * 4000}) + "\n"); open("disk/fill", "w").write("y" * 4096)' 2>/dev/null
"$render" scene.gltf -o out_log.png --log disk/log.jsonl -W 16 -H 12 --spp 1 --engine embree -q 2>log.err
echo "log rc \$?"
python3 -c 'import json,sys; [json.loads(l) for l in open("disk/log.jsonl")]; print("log lines whole")'
umount disk
SH
  unshare -m bash full.sh >full.out 2>&1
  cat full.out >&2
  grep -q "^exr+png rc 2$" full.out && ok || fail "-o x.exr --png on a full disk: not exit 2"
  [ "$(grep -A1 '^exr+png rc' full.out | tail -1 | tr -d ' ')" = "" ] && ok || fail "files left on the full disk: $(grep -A1 '^exr+png rc' full.out | tail -1)"
  grep -q "^log rc 2$" full.out && ok || fail "--log on a full disk: not exit 2"
  grep -q "^log lines whole$" full.out && ok || fail "--log on a full disk left a partial line"
else
  if [ "${CI:-}" = true ]; then fail "no mount namespace (unshare -m, root) for the full-disk cases (CI=true)"
  else echo "unshare -m not permitted: the full-disk cases are left out" >&2; fi
fi

# ---- 6. A dead worker's claim on this host is taken at once ----
sleep 0 & dead=$!; wait $dead
echo "$(hostname) $dead" >claimed_0.png.claim.0
expect 0 - "a claim of a dead local worker" -- scene.gltf -o claimed_%d.png --frames 0:0 --placeholders "${cpu[@]}"
[ -s claimed_0.png ] && ok || fail "the dead worker's frame was skipped"
echo "$(hostname) $$" >live_0.png.claim.0
expect 0 - "a claim of a live local worker" -- scene.gltf -o live_%d.png --frames 0:0 --placeholders "${cpu[@]}"
[ ! -e live_0.png ] && ok || fail "a live worker's frame was taken"
echo "otherhost $dead" >other_0.png.claim.0
expect 0 - "a fresh claim of another host" -- scene.gltf -o other_%d.png --frames 0:0 --placeholders "${cpu[@]}"
[ ! -e other_0.png ] && ok || fail "another host's fresh claim was taken"

# ---- 7. Smaller items ----
long=$(printf 'n%.0s' $(seq 1 236)).png
expect 0 - "a 240-byte output name" -- scene.gltf -o "$long" "${cpu[@]}"
[ -s "$long" ] && ok || fail "the 240-byte output was not written"
ls | grep -q '\.tmp\.' && fail "temporary files left: $(ls | grep '\.tmp\.')" || ok
expect 2 MISSING "a missing --mse-reference, up front" -- scene.gltf -o miss.exr --mse-reference none.exr "${cpu[@]}"
# (the check of the inputs names the frame; the comparison after a render
# would say "cannot compare")
grep -q "of frame 0" "$tmp/stderr" && ! grep -q "cannot compare" "$tmp/stderr" && [ ! -e miss.exr ] \
  && ok || fail "the missing reference was not seen before rendering"
# says MESSAGE: the last line of the run's stderr holds MESSAGE (these
# usage errors have no id: the message names the option at fault).
says() { tail -n 1 "$tmp/stderr" | grep -qF -- "$1" && ok || { fail "the message lacks '$1':"; tail -n 1 "$tmp/stderr" >&2; }; }
expect 2 - "a frame field too wide" -- scene.gltf -o 'f_%99999999999d.png' --frames 1:2 "${cpu[@]}"
says "wider than 32"
expect 2 - "a frame field of 40 #" -- scene.gltf -o "f_$(printf '#%.0s' $(seq 1 40)).png" --frames 1:2 "${cpu[@]}"
says "wider than 32"
expect 2 - "--up parallel to the view" -- scene.gltf -o out.png --eye 0,0,5 --look-at 0,0,0 --up 0,0,1 "${cpu[@]}"
says "--up 0,0,1 is parallel to the view direction"
expect 2 - "--eye at --look-at" -- scene.gltf -o out.png --eye 1,1,1 --look-at 1,1,1 "${cpu[@]}"
says "--eye and --look-at are the same point"
mkgltf thin.gltf tri.bin '' '"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1,"aspectRatio":0.0001}}],'
sed -i 's/"nodes":\[{"mesh":0}\]/"nodes":[{"mesh":0},{"camera":0,"translation":[0,0,3]}]/; s/"scenes":\[{"nodes":\[0\]}\]/"scenes":[{"nodes":[0,1]}]/' thin.gltf
expect 2 - "a camera of aspect 1e-4 without -H" -- thin.gltf -o out.png --engine embree -W 640 --spp 1 -q
says "give -H"
expect 0 - "the same camera with -H" -- thin.gltf -o out.png "${cpu[@]}"
mkgltf ortho.gltf tri.bin '' '"cameras":[{"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":10}}],'
sed -i 's/"nodes":\[{"mesh":0}\]/"nodes":[{"mesh":0},{"camera":0,"translation":[0.3,0.3,3]}]/; s/"scenes":\[{"nodes":\[0\]}\]/"scenes":[{"nodes":[0,1]}]/' ortho.gltf
expect 2 - "an orthographic camera, dirt's camera view" -- ortho.gltf -o out.png -W 16 -H 16 --spp 1
grep -q -- "--views cube" "$tmp/stderr" && ok || fail "the orthographic message does not say --views cube"
expect 0 - "an orthographic camera, embree" -- ortho.gltf -o ortho_embree.exr "${cpu[@]}"
mkgltf notex.gltf tri.bin missing.png
expect 0 - "a missing texture warns" -- notex.gltf -o out.png "${cpu[@]}"
expect 2 STRICT "a missing texture with --strict" -- notex.gltf -o out.png --strict "${cpu[@]}"
printf 'ply\nformat ascii 1.0\nend_header\n' >model.ply
expect 2 FORMAT "a .ply" -- model.ply -o out.png "${cpu[@]}"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 4294967297 2 3\n' >wrap.obj
expect 2 INDEX "an OBJ index of 2^32 + 1" -- wrap.obj -o out.png "${cpu[@]}"
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >nan.obj
expect 2 NOT_FINITE "an OBJ nan coordinate" -- nan.obj -o out.png "${cpu[@]}"
printf '{"asset":{"version":"1.0"}}' >v1.gltf
expect 2 VERSION "asset.version 1.0" -- v1.gltf -o out.png "${cpu[@]}"
printf 'glTF\x01\x00\x00\x00\x30\x00\x00\x00\x1c\x00\x00\x00JSON{"asset":{"version":"2.0"}}' >v1.glb
expect 2 VERSION "a .glb of version 1" -- v1.glb -o out.png "${cpu[@]}"

# The orthographic camera through dirt's cube views (an OpenGL context).
"$render" ortho.gltf -o ortho_dirt.exr -W 16 -H 12 --spp 1 -q --views cube 2>"$tmp/stderr"
rc=$?
if [ $rc -eq 3 ]; then
  [ "${CI:-}" = true ] && fail "no OpenGL context (CI=true)" || echo "no OpenGL context: the cube-view render is left out" >&2
else
  [ $rc -eq 0 ] && ok || { fail "an orthographic camera with --views cube: exit $rc"; cat "$tmp/stderr" >&2; }
fi

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
