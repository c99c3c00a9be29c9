#!/usr/bin/env bash
# The scenes a user brings, through dirt-render as a person runs it:
#  - a .gltf whose extensionsRequired names KHR_draco_mesh_compression (made
#    here) exits 2 naming the extension, with every engine, and writes no
#    image; an ignored extension of extensionsUsed warns once and renders;
#  - ../shared/scenes/cornell/CornellBox-Original.obj: its triangle count
#    (--info) equals the faces' n - 2 counted here with awk; lit by its own
#    emitter (not black against a black background, black with the emitter's
#    Ke zeroed in a copy of its .mtl); DIRT == Embree at the same seed
#    (relMSE < 1e-6; measured ~1e-15);
#  - a glTF made here with noise textures of different, non-power-of-two
#    sizes (3x5 sRGB base colour, 17x4 metallic-roughness, 1x1, 7x2
#    emissive) and UVs that wrap: DIRT == Embree at the same seed (relMSE
#    < 1e-6; measured 1.1e-12 on llvmpipe). The GPU reads the same texels at
#    their own sizes with the C filter's operations; when it sampled a
#    texture array of one common size (resized copies, hardware bilinear)
#    this render measured 5.4e-4.
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
json.dump(scene(['KHR_materials_clearcoat', 'KHR_materials_clearcoat'], None),
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
n=$(grep -c "uses the glTF extension KHR_materials_clearcoat" "$tmp/used.log")
[ "$n" -eq 1 ] || { fail "used.gltf: $n warnings about KHR_materials_clearcoat, expected 1"; cat "$tmp/used.log" >&2; }

# ---- textures at their own sizes -------------------------------------------
# A floor (UVs -1.3 .. 2.6: the lookups wrap) and a back wall, lit by a point
# light and the wall's textured emission; the images are random bytes.
python3 - "$tmp" <<'PY' || fail "writing textured.gltf"
import base64, json, random, struct, sys, zlib
d = sys.argv[1]
rnd = random.Random(5)
def png(w, h):
    px = bytes(rnd.randrange(256) for _ in range(w * h * 4))
    raw = b''.join(b'\x00' + px[y * w * 4:(y + 1) * w * 4] for y in range(h))
    def chunk(t, b):
        return struct.pack('>I', len(b)) + t + b + struct.pack('>I', zlib.crc32(t + b) & 0xffffffff)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
floor = ([-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2], [0, 1, 0] * 4,
         [-1.3, -1.1, 2.6, -1.1, 2.6, 2.3, -1.3, 2.3], [0, 2, 1, 0, 3, 2])
wall = ([-2, 0, -2, 2, 0, -2, 2, 3, -2, -2, 3, -2], [0, 0, 1] * 4,
        [0.1, 0.05, 1.9, 0.05, 1.9, 1.7, 0.1, 1.7], [0, 1, 2, 0, 2, 3])
buf, views, accessors, prims = b'', [], [], []
for m, (pos, nrm, uv, idx) in enumerate((floor, wall)):
    a = len(accessors)
    for data, fmt, typ, comp in ((pos, 'f', 'VEC3', 5126), (nrm, 'f', 'VEC3', 5126),
                                 (uv, 'f', 'VEC2', 5126), (idx, 'H', 'SCALAR', 5123)):
        b = struct.pack('<%d%s' % (len(data), fmt), *data)
        views.append({'buffer': 0, 'byteOffset': len(buf), 'byteLength': len(b)})
        acc = {'bufferView': len(views) - 1, 'componentType': comp, 'type': typ,
               'count': len(data) // {'VEC3': 3, 'VEC2': 2, 'SCALAR': 1}[typ]}
        if len(accessors) == a:
            acc['min'] = [min(pos[k::3]) for k in range(3)]
            acc['max'] = [max(pos[k::3]) for k in range(3)]
        accessors.append(acc)
        buf += b + b'\x00' * (-len(b) % 4)
    prims.append({'attributes': {'POSITION': a, 'NORMAL': a + 1, 'TEXCOORD_0': a + 2},
                  'indices': a + 3, 'material': m})
images = [{'uri': 'data:image/png;base64,' + base64.b64encode(png(w, h)).decode()}
          for (w, h) in ((3, 5), (17, 4), (1, 1), (7, 2))]
g = {'asset': {'version': '2.0'}, 'extensionsUsed': ['KHR_lights_punctual'],
     'scenes': [{'nodes': [0, 1, 2]}],
     'nodes': [{'mesh': 0},
               {'camera': 0, 'translation': [0.3, 1.6, 4.5], 'rotation': [-0.12, 0, 0, 0.9928]},
               {'translation': [0.5, 2.2, 1.0], 'extensions': {'KHR_lights_punctual': {'light': 0}}}],
     'extensions': {'KHR_lights_punctual': {'lights': [
         {'type': 'point', 'intensity': 30, 'color': [1, 0.9, 0.8]}]}},
     'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.9, 'znear': 0.1}}],
     'meshes': [{'primitives': prims}],
     'materials': [
         {'pbrMetallicRoughness': {'baseColorTexture': {'index': 0},
                                   'metallicRoughnessTexture': {'index': 1},
                                   'metallicFactor': 0.6, 'roughnessFactor': 0.9}},
         {'pbrMetallicRoughness': {'baseColorTexture': {'index': 2}, 'metallicFactor': 0.0,
                                   'metallicRoughnessTexture': {'index': 1}},
          'emissiveFactor': [0.4, 0.4, 0.4], 'emissiveTexture': {'index': 3}}],
     'textures': [{'source': i} for i in range(4)], 'images': images,
     'buffers': [{'byteLength': len(buf),
                  'uri': 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()}],
     'bufferViews': views, 'accessors': accessors}
json.dump(g, open(d + '/textured.gltf', 'w'))
PY
tex=(-W 48 -H 36 --spp 4 --seed 7 --bounces 3)
"$render" "$tmp/textured.gltf" -o "$tmp/tex_embree.exr" --engine embree "${tex[@]}" >"$tmp/log" 2>&1 ||
  { fail "embree render of textured.gltf: exit $?"; cat "$tmp/log" >&2; }
"$compare" --not-black "$tmp/tex_embree.exr" 0.005 || fail "textured.gltf renders black"
"$render" "$tmp/textured.gltf" -o "$tmp/tex_dirt.exr" --engine dirt "${tex[@]}" >"$tmp/log" 2>&1
rc=$?
if [ $rc -eq 3 ]; then
  if [ "${CI:-}" = true ]; then fail "CI=true: no OpenGL context is a failure"; else
    echo "no OpenGL context: the textured DIRT render is skipped" >&2; fi
else
  [ $rc -eq 0 ] || { fail "dirt render of textured.gltf: exit $rc"; cat "$tmp/log" >&2; }
  "$compare" "$tmp/tex_dirt.exr" "$tmp/tex_embree.exr" 1e-6 ||
    fail "DIRT differs from Embree on textures of different sizes"
fi

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
