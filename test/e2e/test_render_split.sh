#!/usr/bin/env bash
# Scenes past one storage block, as a person runs dirt-render:
#  - DIRT_MAX_BLOCK_BYTES lowers the storage block every size check and
#    split uses: a room of about 5000 triangles (perf/make-scale-scene.py)
#    at 96x72 runs with its arrays in several parts (the log says so: dirt
#    at tile size 1 with blocks of 192 KiB: vertices, candidates, id nodes,
#    list heads, depth pyramid; mmrt with blocks of 256 KiB: vertices,
#    bucket heads, id and data nodes; the raster preview: its vertices, drawn
#    part by part), and its EXR's pixels equal the unsplit one's bit for
#    bit (exr_compare --exact; the headers differ: provenance), for dirt
#    (raster and compute build), mmrt and the raster preview; the
#    split DIRT render equals Embree's with the same seed (relMSE < 1e-4);
#  - the same room normal-mapped and textured (make-scale-scene.py
#    --normal-map: 2 textures of 256 x 256, tangents generated) with blocks
#    of 192 KiB: the frame's tangents and the scene's texels are split too
#    (read by Shade, and the texels by the traces' alpha test builds), and
#    the EXR equals the unsplit one bit for bit for dirt (raster and compute
#    build) and mmrt (at 64x48: its data nodes grow with the pixels); the split DIRT render equals Embree's (relMSE < 1e-4);
#    textures past one split array (1024 x 1024, blocks of 512 KiB) exit 1
#    before the build, saying to make the textures smaller or fewer;
#  - a malformed DIRT_MAX_BLOCK_BYTES is warned about and ignored;
#  - past what one array holds (blocks of 8 KiB: the vertices need more than
#    8 parts) the render exits 1 before any pass with one error saying what
#    to change, and writes nothing;
#  - --max-scene-memory: a scene past the budget (20000 triangles, 1 MiB)
#    exits 2 naming the option and saying to raise it, nothing written; with
#    the budget raised it renders; a bad size exits 2.
# Usage: test_render_split.sh DIRT_RENDER EXR_COMPARE SOURCE_ROOT
set -u
render=$1 compare=$2 root=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

"${PYTHON:-/usr/bin/python3}" "$root/perf/make-scale-scene.py" "$tmp/room.glb" 5000 >/dev/null ||
  { echo "cannot write the scene (python3-numpy?)" >&2; exit 1; }
common=(-W 96 -H 72 --spp 2 --seed 5 --bounces 3 -S 1 -B 8)
"$render" "$tmp/room.glb" -o "$tmp/embree.exr" --engine embree "${common[@]}" >"$tmp/log" 2>&1
rc=$?
if [ $rc -eq 3 ]; then
  if [ "${CI:-}" = true ]; then echo "CI=true: no OpenGL context is a failure" >&2; exit 1; fi
  echo "no OpenGL context: skipping" >&2; exit 77
fi
[ $rc -eq 0 ] || { fail "embree render exit $rc"; cat "$tmp/log" >&2; }

for run in "dirt --build raster" "dirt --build compute" "mmrt -B 4" "raster"; do
  set -- $run
  name=$1
  [ "${2:-}" = --build ] && name=$1_$3
  "$render" "$tmp/room.glb" -o "$tmp/$name.exr" --engine $run "${common[@]}" >"$tmp/log" 2>&1 ||
    { fail "$name: unsplit render"; cat "$tmp/log" >&2; }
  grep -q "texel buffers" "$tmp/log" && fail "$name: the unsplit render split an array"
  block=192K
  [ "$name" = mmrt ] && block=256K
  DIRT_MAX_BLOCK_BYTES=$block "$render" "$tmp/room.glb" -o "$tmp/${name}_split.exr" \
    --engine $run "${common[@]}" >"$tmp/log" 2>&1 ||
    { fail "$name: split render"; cat "$tmp/log" >&2; }
  want="vertices"
  case $name in
    dirt*) want="vertices DIRT.build.s.candidates DIRT.id.nodes DIRT.list.heads depth.bounds" ;;
    mmrt) want="vertices MMRT.bucket.heads MMRT.id.nodes MMRT.data.nodes" ;;
    raster) want="raster.preview.s.vertices" ;;
  esac
  for w in $want; do
    grep -Eq "the (scene.s )?$w.* in [2-8] parts of " "$tmp/log" ||
      { fail "$name: the $w were not split"; grep "parts of" "$tmp/log" >&2; }
  done
  "$compare" --exact "$tmp/$name.exr" "$tmp/${name}_split.exr" >/dev/null ||
    fail "$name: the split EXR differs from the unsplit one"
done
"$compare" "$tmp/dirt_raster_split.exr" "$tmp/embree.exr" 1e-4 ||
  fail "the split DIRT render differs from Embree's"

# Normal-mapped and textured: the tangents and the texels split as well.
"${PYTHON:-/usr/bin/python3}" "$root/perf/make-scale-scene.py" "$tmp/nmap.glb" 5000 \
  --normal-map >/dev/null || fail "cannot write the normal-mapped scene"
"$render" "$tmp/nmap.glb" -o "$tmp/nmap_embree.exr" --engine embree "${common[@]}" \
  >"$tmp/log" 2>&1 || { fail "nmap: embree render"; cat "$tmp/log" >&2; }
for run in "dirt --build raster" "dirt --build compute" "mmrt -B 4"; do
  set -- $run
  name=nmap_$1
  [ "${2:-}" = --build ] && name=nmap_$1_$3
  # MMRT's data nodes grow with the pixels: a smaller image keeps them
  # within 8 parts of the blocks that split the tangents.
  size=()
  [ $1 = mmrt ] && size=(-W 64 -H 48)
  "$render" "$tmp/nmap.glb" -o "$tmp/$name.exr" --engine $run "${common[@]}" "${size[@]}" \
    >"$tmp/log" 2>&1 || { fail "$name: unsplit render"; cat "$tmp/log" >&2; }
  grep -q "texel buffers" "$tmp/log" && fail "$name: the unsplit render split an array"
  DIRT_MAX_BLOCK_BYTES=192K "$render" "$tmp/nmap.glb" -o "$tmp/${name}_split.exr" \
    --engine $run "${common[@]}" "${size[@]}" >"$tmp/log" 2>&1 ||
    { fail "$name: split render"; cat "$tmp/log" >&2; }
  for w in "scene's texels" "frame's tangents"; do
    grep -Eq "the $w: .* in [2-8] parts of " "$tmp/log" ||
      { fail "$name: the $w were not split"; grep "parts of" "$tmp/log" >&2; }
  done
  "$compare" --exact "$tmp/$name.exr" "$tmp/${name}_split.exr" >/dev/null ||
    fail "$name: the split EXR differs from the unsplit one"
done
"$compare" "$tmp/nmap_dirt_raster_split.exr" "$tmp/nmap_embree.exr" 1e-4 ||
  fail "nmap: the split DIRT render differs from Embree's"
"${PYTHON:-/usr/bin/python3}" "$root/perf/make-scale-scene.py" "$tmp/nmap_big.glb" 5000 \
  --normal-map --texture-size 1024 >/dev/null || fail "cannot write the 1024^2 textures"
DIRT_MAX_BLOCK_BYTES=512K "$render" "$tmp/nmap_big.glb" -o "$tmp/toobig.exr" "${common[@]}" \
  >"$tmp/log" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "texels past one array: exit $rc, want 1"
grep -q "the scene's texels need .* more than this GPU holds in one array" "$tmp/log" &&
  grep -q "make the scene's textures smaller or fewer" "$tmp/log" ||
  { fail "texels past one array: no clear error"; cat "$tmp/log" >&2; }
grep -Eq "DIRT (build|list)|sample" "$tmp/log" && fail "texels past one array: work before the error"
[ -e "$tmp/toobig.exr" ] && fail "texels past one array: a failed render left its output"

DIRT_MAX_BLOCK_BYTES=lots "$render" "$tmp/room.glb" -o "$tmp/warned.png" "${common[@]}" \
  >"$tmp/log" 2>&1 || fail "a malformed DIRT_MAX_BLOCK_BYTES failed the render"
grep -q "DIRT_MAX_BLOCK_BYTES=lots is not a size" "$tmp/log" || fail "no warning for 'lots'"

DIRT_MAX_BLOCK_BYTES=8K "$render" "$tmp/room.glb" -o "$tmp/toobig.exr" "${common[@]}" \
  >"$tmp/log" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "past what one array holds: exit $rc, want 1"
[ "$(grep -c "error" "$tmp/log")" -ge 1 ] && grep -q "more than this GPU holds in one array" \
  "$tmp/log" && grep -q "fewer triangles" "$tmp/log" || { fail "no clear error"; cat "$tmp/log" >&2; }
grep -q "sample" "$tmp/log" && fail "past what one array holds: samples ran before the error"
[ -e "$tmp/toobig.exr" ] && fail "a failed render left its output"

"${PYTHON:-/usr/bin/python3}" "$root/perf/make-scale-scene.py" "$tmp/big.glb" 20000 >/dev/null
"$render" "$tmp/big.glb" -o "$tmp/budget.png" --max-scene-memory 1M "${common[@]}" \
  >"$tmp/log" 2>&1
rc=$?
[ $rc -eq 2 ] || fail "past the load budget: exit $rc, want 2"
grep -q "raise the budget with --max-scene-memory" "$tmp/log" || { fail "no advice"; cat "$tmp/log" >&2; }
[ -e "$tmp/budget.png" ] && fail "a refused scene left its output"
"$render" "$tmp/big.glb" -o "$tmp/budget.png" --max-scene-memory 64M "${common[@]}" \
  >"$tmp/log" 2>&1 || { fail "--max-scene-memory 64M"; cat "$tmp/log" >&2; }
for bad in 12X 0 -5 0.5 1KB; do
  "$render" "$tmp/room.glb" -o "$tmp/bad.png" --max-scene-memory $bad >"$tmp/log" 2>&1
  rc=$?
  [ $rc -eq 2 ] && grep -q -- "--max-scene-memory" "$tmp/log" ||
    fail "--max-scene-memory $bad: exit $rc"
done

[ $fails -eq 0 ] && echo "render split: all checks passed"
exit $((fails > 0))
