#!/usr/bin/env bash
# The scenes a user brings, through dirt-render as a person runs it:
#  - a .gltf whose extensionsRequired names KHR_draco_mesh_compression (made
#    here) exits 2 naming the extension, with every engine, and writes no
#    image; an ignored extension of extensionsUsed warns once and renders;
#  - ../shared/scenes/cornell/CornellBox-Original.obj: its triangle count
#    (--info) equals the faces' n - 2 counted here with awk; lit by its own
#    emitter (not black against a black background, black with the emitter's
#    Ke zeroed in a copy of its .mtl); DIRT == Embree at the same seed
#    (relMSE < 1e-6; measured ~1e-15).
# Usage: test_render_scenes.sh DIRT_RENDER EXR_COMPARE
set -u
render=$1
compare=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# ---- an unsupported required extension ----------------------------------
# A one-triangle glTF with the Draco extension required (the buffer holds 3
# float positions; a Draco file would keep them compressed in the extension).
python3 - "$tmp" <<'PY' || fail "writing the glTF files"
import base64, json, struct, sys
d = sys.argv[1]
buf = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
uri = 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()
def scene(used, required, prim_ext=None):
    prim = {'attributes': {'POSITION': 0}}
    if prim_ext:
        prim['extensions'] = prim_ext
    g = {'asset': {'version': '2.0'}, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0}],
         'meshes': [{'primitives': [prim]}],
         'buffers': [{'byteLength': len(buf), 'uri': uri}],
         'bufferViews': [{'buffer': 0, 'byteLength': len(buf)}],
         'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC3',
                        'min': [0, 0, 0], 'max': [1, 1, 0]}],
         'materials': [{'emissiveFactor': [1, 1, 1]}]}
    g['meshes'][0]['primitives'][0]['material'] = 0
    if used:
        g['extensionsUsed'] = used
    if required:
        g['extensionsRequired'] = required
    return g
draco = {'KHR_draco_mesh_compression': {'bufferView': 0, 'attributes': {'POSITION': 0}}}
json.dump(scene(['KHR_draco_mesh_compression'], ['KHR_draco_mesh_compression'], draco),
          open(d + '/draco.gltf', 'w'))
json.dump(scene(['KHR_texture_transform', 'KHR_texture_transform'], None),
          open(d + '/used.gltf', 'w'))
PY
for engine in embree dirt mmrt raster; do
  "$render" "$tmp/draco.gltf" -o "$tmp/draco_$engine.exr" --engine "$engine" -W 16 -H 12 --spp 1 \
    >"$tmp/draco.log" 2>&1
  rc=$?
  [ $rc -eq 2 ] || { fail "draco.gltf --engine $engine: exit $rc, expected 2"; cat "$tmp/draco.log" >&2; }
  grep -q "requires the glTF extension KHR_draco_mesh_compression" "$tmp/draco.log" ||
    { fail "draco.gltf --engine $engine: the error does not name the extension"; cat "$tmp/draco.log" >&2; }
  [ -e "$tmp/draco_$engine.exr" ] && fail "draco.gltf --engine $engine left an image"
done
"$render" --info "$tmp/draco.gltf" >"$tmp/draco.log" 2>&1
rc=$?
[ $rc -eq 2 ] || fail "--info draco.gltf: exit $rc, expected 2"
"$render" "$tmp/used.gltf" -o "$tmp/used.exr" --engine embree -W 16 -H 12 --spp 1 \
  >"$tmp/used.log" 2>&1 || { fail "used.gltf: exit $?"; cat "$tmp/used.log" >&2; }
n=$(grep -c "uses the glTF extension KHR_texture_transform" "$tmp/used.log")
[ "$n" -eq 1 ] || { fail "used.gltf: $n warnings about KHR_texture_transform, expected 1"; cat "$tmp/used.log" >&2; }

# ---- the OBJ Cornell box --------------------------------------------------
shared=${DIRT_SHARED_DIR:-}
cornell=$shared/scenes/cornell/CornellBox-Original.obj
if [ -z "$shared" ] || [ ! -f "$cornell" ]; then
  if [ "${CI:-}" = true ]; then
    fail "CI=true but the shared scene $cornell is missing"
  else
    echo "shared scenes absent: the OBJ checks are skipped" >&2
  fi
  echo "$fails failed" >&2
  [ $fails -eq 0 ] || exit 1
  [ "${CI:-}" = true ] && exit 1
  exit 77
fi

# Triangles of the file, counted from its text: n - 2 per face of n corners.
want=$(awk '$1 == "f" && NF >= 4 { t += NF - 3 } END { print t + 0 }' "$cornell")
got=$("$render" --info "$cornell" 2>"$tmp/info.log" | awk '$1 == "triangles" { print $2 }')
[ "$want" = 36 ] || fail "awk counts $want triangles in $cornell (CREDITS.md says 36)"
[ "$got" = "$want" ] || { fail "--info says $got triangles, the file has $want"; cat "$tmp/info.log" >&2; }
[ -s "$tmp/info.log" ] && { fail "loading $cornell warned"; cat "$tmp/info.log" >&2; }

common=(-W 48 -H 36 --spp 4 --seed 7 --bounces 3 --background 0,0,0)
"$render" "$cornell" -o "$tmp/embree.exr" --engine embree "${common[@]}" >"$tmp/log" 2>&1 ||
  { fail "embree render of the OBJ: exit $?"; cat "$tmp/log" >&2; }
"$compare" --not-black "$tmp/embree.exr" 0.005 || fail "the OBJ Cornell box is black"
# Without its emitter (a copy with Ke zeroed) nothing lights it.
mkdir -p "$tmp/dark"
cp "$cornell" "$tmp/dark/"
sed 's/^\([[:space:]]*\)Ke .*/\1Ke 0 0 0/' "${cornell%.obj}.mtl" >"$tmp/dark/CornellBox-Original.mtl"
"$render" "$tmp/dark/CornellBox-Original.obj" -o "$tmp/dark.exr" --engine embree "${common[@]}" \
  >"$tmp/log" 2>&1 || { fail "embree render of the dark copy: exit $?"; cat "$tmp/log" >&2; }
if "$compare" --not-black "$tmp/dark.exr" 1e-9 >/dev/null; then
  fail "the copy without emission is not black: something else lights the box"
fi

"$render" "$cornell" -o "$tmp/dirt.exr" --engine dirt "${common[@]}" >"$tmp/log" 2>&1
rc=$?
if [ $rc -eq 3 ]; then
  if [ "${CI:-}" = true ]; then fail "CI=true: no OpenGL context is a failure"; else
    echo "no OpenGL context: the DIRT render is skipped" >&2; fi
else
  [ $rc -eq 0 ] || { fail "dirt render of the OBJ: exit $rc"; cat "$tmp/log" >&2; }
  "$compare" "$tmp/dirt.exr" "$tmp/embree.exr" 1e-6 || fail "DIRT differs from Embree on the OBJ"
fi
echo "$fails failed" >&2
[ $fails -eq 0 ]
