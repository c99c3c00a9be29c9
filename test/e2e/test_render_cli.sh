#!/usr/bin/env bash
# dirt-render as a user runs it: --help, --version, and every kind of bad
# input exits 2 with a one-line reason and leaves no file (not even a
# temporary one) behind; good inputs write real images whose EXR headers and
# stats files record what made them (read back with OpenEXR's own API).
#   test_render_cli.sh PATH/TO/dirt-render PATH/TO/exr_compare
set -u
render=$1 exr=$2
json=$(dirname "$0")/json_check.py
tmp=$(mktemp -d /tmp/dirt-e2e-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0

ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }

# expect_rc RC DESCRIPTION -- ARGS...: runs dirt-render, checks the exit code,
# and for failures that stderr's last line names the program.
expect_rc() {
  local want=$1 what=$2; shift 3
  "$render" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  if [ "$rc" -ne "$want" ]; then
    fail "$what: exit $rc, want $want"; cat "$tmp/stderr" >&2; return
  fi
  if [ "$want" -ne 0 ] && ! tail -n 1 "$tmp/stderr" | grep -q '^dirt-render: '; then
    fail "$what: no one-line reason on stderr"; cat "$tmp/stderr" >&2; return
  fi
  ok
}

# no_leftovers DIR: no image and no temporary file was left in DIR.
no_leftovers() {
  if [ -n "$(ls -A "$1")" ]; then fail "files left in $1: $(ls -A "$1")"; else ok; fi
}

# mkgltf NAME POSITION_BYTES INDEX_BYTES [MATERIAL_JSON]: a one-triangle glTF
# with an embedded base64 buffer (bytes given as printf escapes).
mkgltf() {
  local name=$1 pos=$2 idx=$3 extra=${4:-}
  local b64; b64=$(printf "$pos$idx" | base64 -w0)
  local mat='' matref=''
  if [ -n "$extra" ]; then mat=",$extra"; matref=',"material":0'; fi
  cat > "$tmp/$name" <<JSON
{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1$matref}]}],
 "buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,$b64"}],
 "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":8}],
 "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
              {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]$mat}
JSON
}
ZERO='\x00\x00\x00\x00' ONE='\x00\x00\x80\x3f' NAN='\x00\x00\xc0\x7f'
GOODPOS="$ZERO$ZERO$ZERO$ONE$ZERO$ZERO$ZERO$ONE$ZERO"
mkgltf good.gltf "$GOODPOS" '\x00\x00\x01\x00\x02\x00\x00\x00'
mkgltf badindex.gltf "$GOODPOS" '\x00\x00\x01\x00\x05\x00\x00\x00'
mkgltf nan.gltf "$ZERO$ZERO$ZERO$NAN$ZERO$ZERO$ZERO$ONE$ZERO" '\x00\x00\x01\x00\x02\x00\x00\x00'
mkgltf notex.gltf "$GOODPOS" '\x00\x00\x01\x00\x02\x00\x00\x00' \
  '"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[{"uri":"missing.png"}]'
printf 'glTF\x02\x00\x00\x00\x00\x10\x00\x00\x10\x00\x00\x00JSON{"asset"' > "$tmp/truncated.glb"
printf '{"asset": {"version": "2.0"' > "$tmp/broken.gltf"

out=$tmp/out; mkdir -p "$out"

# --help
expect_rc 0 "--help" -- --help
grep -q '^Usage: dirt-render' "$tmp/stdout" && ok || fail "--help prints no usage"

# --version: the version and commit, then the renderer (exit 3 without a
# GL context, the version printed all the same).
"$render" --version >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
{ [ $rc -eq 0 ] || [ $rc -eq 3 ]; } && ok || fail "--version exit $rc"
head -n 1 "$tmp/stdout" | grep -Eq '^dirt-render [0-9]+\.[0-9]+\.[0-9]+ \(commit [^ ]+\)$' && ok \
  || fail "--version's first line: $(head -n 1 "$tmp/stdout")"
grep -q '^OpenGL renderer: ' "$tmp/stdout" && ok || fail "--version names no renderer"

# bad options
expect_rc 2 "unknown option" -- --bogus -o "$out/a.png"
expect_rc 2 "no output" --
expect_rc 2 "bad extension" -- -o "$out/a.bmp"
expect_rc 2 "width not a number" -- -o "$out/a.png" -W abc
expect_rc 2 "width zero" -- -o "$out/a.png" -W 0
# The environment light: a bad map, two environments, knobs without a map.
expect_rc 2 "missing environment map" -- -o "$out/a.png" --env "$out/none.exr"
expect_rc 2 "environment map of the wrong type" -- -o "$out/a.png" --env "$out/map.png"
printf 'not an exr' >"$tmp/bad.exr"
expect_rc 2 "malformed environment map" -- -o "$out/a.png" --env "$tmp/bad.exr"
expect_rc 2 "--env and --background" -- -o "$out/a.png" --env sky --background 1,1,1
expect_rc 2 "--env-intensity without a map" -- -o "$out/a.png" --env-intensity 2
expect_rc 2 "negative --env-intensity" -- -o "$out/a.png" --env sky --env-intensity -1
[ ! -e "$out/a.png" ] && ok || fail "a refused run wrote its output"
expect_rc 2 "missing value" -- -o "$out/a.png" -W
expect_rc 2 "unknown engine" -- -o "$out/a.png" --engine optix
expect_rc 2 "frames without pattern" -- -o "$out/a.png" --frames 0:3
expect_rc 2 "frames reversed" -- -o "$out/a_%d.png" --frames 3:1
expect_rc 2 "two scenes" -- "$tmp/good.gltf" "$tmp/good.gltf" -o "$out/a.png"
expect_rc 2 "bad mode" -- -o "$out/a.png" --mode xyz
expect_rc 2 "zero spp" -- -o "$out/a.png" --spp 0
expect_rc 2 "more large primitives than kept" -- -o "$out/a.png" --large 17
expect_rc 2 "stats not json" -- -o "$out/a.png" --stats "$out/s.txt"
expect_rc 2 "short background" -- -o "$out/a.png" --background 1,2
expect_rc 2 "bad fetch" -- -o "$out/a.png" --fetch magic
expect_rc 2 "bad tile size" -- -o "$out/a.png" --tile 3
expect_rc 2 "direct visibility without camera view" -- -o "$out/a.png" --views cube --direct-visibility
# Directories are made, but not under a file; every output is proven
# creatable (a temp file is made) before any work, so nothing is left.
: >"$tmp/plainfile"
expect_rc 2 "stats dir under a file" -- -o "$out/a.png" --stats "$tmp/plainfile/dir/s.json"
no_leftovers "$out"
expect_rc 2 "stats in /proc (even as root)" -- -o "$out/a.png" --stats /proc/s.json
no_leftovers "$out"
expect_rc 2 "log not jsonl" -- -o "$out/a.png" --log "$out/l.txt"
expect_rc 2 "bad frame list" -- -o "$out/a_####.png" --frames 1,x
expect_rc 2 "two frame fields" -- -o "$out/a_##_%d.png" --frames 1:2
expect_rc 2 "chunk without frames" -- -o "$out/a.png" --chunk 1/2
expect_rc 2 "chunk out of range" -- -o "$out/a_#.png" --frames 1:4 --chunk 3/2
expect_rc 2 "slurm chunk outside slurm" -- -o "$out/a_#.png" --frames 1:4 --chunk slurm
expect_rc 2 "bad --max-scene-memory" -- -o "$out/a.png" --max-scene-memory 5X
expect_rc 2 "fractional --max-scene-memory" -- -o "$out/a.png" --max-scene-memory 0.5
# The scene's budget: good.gltf's 3 vertices and 1 triangle need more than 16 bytes.
expect_rc 2 "scene over --max-scene-memory" -- "$tmp/good.gltf" -o "$out/a.png" --max-scene-memory 16
grep -q 'max-scene-memory' "$tmp/stderr" && ok || fail "the budget's error does not name --max-scene-memory"
no_leftovers "$out"

# bad files
expect_rc 2 "missing scene" -- "$tmp/nope.gltf" -o "$out/a.png"
expect_rc 2 "truncated glb" -- "$tmp/truncated.glb" -o "$out/a.png"
expect_rc 2 "malformed json" -- "$tmp/broken.gltf" -o "$out/a.png"
expect_rc 2 "index out of range" -- "$tmp/badindex.gltf" -o "$out/a.png"
expect_rc 2 "NaN position" -- "$tmp/nan.gltf" -o "$out/a.png"
no_leftovers "$out"

# unwritable outputs
expect_rc 2 "output directory under a file" -- -o "$tmp/plainfile/dir/a.png"
mkdir -p "$tmp/isdir.png"
expect_rc 2 "output is a directory" -- -o "$tmp/isdir.png"
expect_rc 2 "camera out of range" -- -o "$out/a.png" --camera 99
no_leftovers "$out"

# The Embree engine needs no GPU: EXR with AOVs and the stats JSON.
expect_rc 0 "embree engine" -- --engine embree -o "$out/e.exr" -W 16 -H 12 --spp 2 --stats "$out/e.json"
head -c 4 "$out/e.exr" | od -An -tx1 | grep -q '76 2f 31 01' && ok || fail "e.exr is not an EXR"
# Provenance: every attribute present and not empty, with this run's values.
prov=(dirt.scene dirt.engine dirt.seed dirt.samples dirt.time dirt.device dirt.command_line
  dirt.version dirt.commit)
"$exr" --attrs "$out/e.exr" "${prov[@]}" >"$tmp/attrs" && ok || { fail "e.exr's provenance"; cat "$tmp/attrs" >&2; }
grep -qx 'dirt.engine=embree' "$tmp/attrs" && grep -qx 'dirt.scene=default' "$tmp/attrs" &&
  grep -qx 'dirt.seed=0' "$tmp/attrs" && grep -qx 'dirt.samples=2' "$tmp/attrs" &&
  grep -qx 'dirt.device=CPU' "$tmp/attrs" &&
  grep -qx "dirt.command_line=$render --engine embree -o $out/e.exr -W 16 -H 12 --spp 2 --stats $out/e.json" "$tmp/attrs" \
  && ok || { fail "e.exr's provenance values"; cat "$tmp/attrs" >&2; }
grep -aq 'albedo.R' "$out/e.exr" && grep -aq 'N.X' "$out/e.exr" && ok || fail "e.exr lacks the AOV channels"
"$json" "$out/e.json" 'd["engine"] == "embree" and d["device"] == "CPU"' \
  'd["build_ms"] > 0 and d["mrays_per_s"] > 0' \
  'd["rays"] >= 16 * 12 * 2 and d["spp"] == 2 and d["width"] == 16 and d["height"] == 12' \
  'all(p["clock"] == "cpu" for p in d["passes"])' \
  'all(d["provenance"][k] for k in ("scene", "engine", "seed", "samples", "time", "device", "command_line", "version", "commit"))' \
  'd["provenance"]["engine"] == "embree" and d["provenance"]["seed"] == "0" and d["frames"][0]["seed"] == 0' \
  && ok || fail "e.json figures"
rm -f "$out"/e.*

# Good inputs need a GL context; without one the program says so with exit 3.
"$render" -o "$out/default.png" -W 64 -H 48 --spp 2 >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
if [ $rc -eq 3 ]; then
  echo "no OpenGL context: skipping the rendering half" >&2
  echo "$passes passed, $fails failed"
  [ $fails -eq 0 ] && exit 77 || exit 1
fi
[ $rc -eq 0 ] && ok || { fail "default render exit $rc"; cat "$tmp/stderr" >&2; }
head -c 8 "$out/default.png" | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a' && ok || fail "default.png is not a PNG"
grep -q "wrote $out/default.png" "$tmp/stdout" && ok || fail "output path not printed"

expect_rc 0 "exr + png preview, stats" -- -o "$out/d.exr" --png -W 32 -H 24 --spp 2 --stats "$out/d.json"
# The stats: figures that add up (32x24, 2 spp, DIRT's structure (no bucket
# occupancy masks without --bucket-masks: 0 bytes) + the
# integrator's 360 bytes per pixel and 292 bytes (ray batch headers,
# paths per event), its environment table, empty here (36
# bytes), and the scene's texel buffer: the default scene has no textures,
# so its 16-byte header; and its tangent table: no normal maps, one 16-byte
# record), each pass tagged with its clock.
"$json" "$out/d.json" 'd["engine"] == "dirt" and d["frames_rendered"] == 1' \
  'all(d[k] > 0 for k in ("build_ms", "trace_ms", "fetch_ms", "shade_ms", "mrays_per_s"))' \
  'd["rays"] >= 32 * 24 * 2 and d["aborted_rays"] == 0 and d["spp"] == 2' \
  'd["paths_per_event"][0] == 32 * 24 * 2 and len(d["paths_per_event"]) == 5' \
  'all(a >= b for a, b in zip(d["paths_per_event"], d["paths_per_event"][1:]))' \
  'd["bytes_total"] == sum(b["used"] for b in d["buffers"])' \
  'd["bytes_total"] == sum(d["bytes"][k] for k in ("vertices", "depth bounds", "list heads", "id nodes", "candidates", "large grid", "bucket masks")) + 32 * 24 * 360 + 292 + 36 + 16 + 16' \
  'd["bytes"]["bucket masks"] == 0 and "bucket masks" not in [b["name"] for b in d["buffers"] if b["used"]]' \
  '[(b["used"], b["allocated"]) for b in d["buffers"] if b["name"] == "model tangents"] == [(16, 16)]' \
  '[b["used"] for b in d["buffers"] if b["name"] == "pt environment"] == [36]' \
  '[(b["used"], b["allocated"]) for b in d["buffers"] if b["name"] == "model texels"] == [(16, 16)]' \
  'd["samples_np"] > 0 and d["frames"][0]["samples"] == 2' \
  'all(p["clock"] in ("gpu", "cpu") and p["ms"] >= 0 for p in d["passes"])' \
  'set(p["name"] for p in d["passes"]) >= {"depth bounds", "fill primitives", "trace", "fetch", "shade"}' \
  && ok || fail "d.json figures"
# Work counters (--count-work): per ray type in each frame's stats, the
# image unchanged bit for bit; none without the option; the raster preview
# traces no rays (exit 2).
expect_rc 0 "count work" -- -o "$out/w.exr" -W 32 -H 24 --spp 2 --count-work --stats "$out/w.json"
"$exr" --exact "$out/w.exr" "$out/d.exr" && ok || fail "--count-work changed the image"
"$json" "$out/w.json" \
  'set(d["frames"][0]["work"]) == {"primary", "visibility", "specular", "glossy", "diffuse"}' \
  'd["frames"][0]["work"]["primary"]["rays"] == 32 * 24' \
  'all(w["triangle_tests"] > 0 and w["tiles"] > 0 and w["hiz_steps"] >= w["tiles"] and w["list_nodes"] > 0 for w in d["frames"][0]["work"].values())' \
  'all(w["embree"]["rays"] == w["rays"] and w["embree"]["bvh_nodes"] > 0 and w["embree"]["triangle_tests"] > 0 for w in d["frames"][0]["work"].values())' \
  && ok || fail "w.json work counts"
"$json" "$out/d.json" '"work" not in d["frames"][0]' && ok || fail "work counted without --count-work"
expect_rc 0 "count work, mmrt" -- --engine mmrt -o "$out/wm.png" -W 32 -H 24 --spp 1 --count-work --stats "$out/wm.json"
"$json" "$out/wm.json" \
  'all(w["fragments"] > 0 and w["pixels"] > 0 and w["hiz_steps"] > 0 and w["triangle_tests"] == 0 for w in d["frames"][0]["work"].values())' \
  && ok || fail "wm.json work counts"
expect_rc 0 "count work, embree" -- --engine embree -o "$out/we.png" -W 32 -H 24 --spp 1 --count-work --stats "$out/we.json"
"$json" "$out/we.json" \
  'all(w["bvh_nodes"] > 0 and w["triangle_tests"] > 0 and "embree" not in w for w in d["frames"][0]["work"].values())' \
  && ok || fail "we.json work counts"
expect_rc 2 "count work with the raster engine" -- --engine raster --count-work -o "$out/r3.png"
# The large primitives' grid (--large-grid): the same image bit for bit;
# its bytes in the stats (none without it); fewer triangle tests than the
# default (every ray tests every large primitive) and more Hi-Z steps (its
# cells) on every ray type; the same tiles and list nodes on closest-hit
# rays (an any-hit ray stops at the first hit it meets, which depends on
# the order of a list's entries: a build's, not fixed).
expect_rc 0 "large primitives' grid" -- -o "$out/lg.exr" -W 32 -H 24 --spp 2 --large-grid --count-work --stats "$out/lg.json"
"$exr" --exact "$out/lg.exr" "$out/d.exr" && ok || fail "--large-grid changed the image"
"$json" "$out/lg.json" \
  'd["bytes"]["large grid"] > 0 and d["bytes"]["large grid"] % 8 == 0' \
  'd["bytes_total"] == sum(b["used"] for b in d["buffers"])' \
  '[b["used"] for b in d["buffers"] if b["name"] == "large primitives\x27 grid"] == [d["bytes"]["large grid"]]' \
  && ok || fail "lg.json: the grid's bytes"
"$json" "$out/d.json" 'd["bytes"]["large grid"] == 0' && ok || fail "d.json: a grid without --large-grid"
python3 - "$out/w.json" "$out/lg.json" <<'PY' && ok || fail "--large-grid's work counts"
import json, sys
off, on = (json.load(open(p))["frames"][0]["work"] for p in sys.argv[1:])
for t in off:
    a, b = off[t], on[t]
    assert a["rays"] == b["rays"], t
    assert t == "visibility" or (a["tiles"] == b["tiles"] and a["list_nodes"] == b["list_nodes"]), t
    assert b["triangle_tests"] < a["triangle_tests"] and b["hiz_steps"] > a["hiz_steps"], (t, a, b)
PY
# Sub-tile rectangles (--sub-tiles): the same image bit for bit, alone and
# with the large primitives' grid and adaptive depth buckets; the same list
# nodes read on closest-hit rays, no more triangle tests on any ray type and
# fewer in all.
expect_rc 0 "sub-tile rectangles" -- -o "$out/st.exr" -W 32 -H 24 --spp 2 --sub-tiles --count-work --stats "$out/st.json"
"$exr" --exact "$out/st.exr" "$out/d.exr" && ok || fail "--sub-tiles changed the image"
expect_rc 0 "sub-tile rectangles with the grid, adaptive buckets" -- -o "$out/st2.exr" -W 32 -H 24 --spp 2 --sub-tiles --large-grid --depth-buckets adaptive
"$exr" --exact "$out/st2.exr" "$out/d.exr" && ok || fail "--sub-tiles --large-grid --depth-buckets adaptive changed the image"
python3 - "$out/w.json" "$out/st.json" <<'PY' && ok || fail "--sub-tiles' work counts"
import json, sys
off, on = (json.load(open(p))["frames"][0]["work"] for p in sys.argv[1:])
for t in off:
    a, b = off[t], on[t]
    assert a["rays"] == b["rays"] and a["tiles"] == b["tiles"], t
    assert t == "visibility" or a["list_nodes"] == b["list_nodes"], t
    assert t == "visibility" or b["triangle_tests"] <= a["triangle_tests"], (t, a, b)
assert sum(on[t]["triangle_tests"] for t in on) < sum(off[t]["triangle_tests"] for t in off)
PY
# Bucket occupancy masks (--bucket-masks): the same image bit for bit, alone
# and with sub-tile rectangles, the large primitives' grid and adaptive depth
# buckets; their bytes (4 per tile: the heads over B, 8 on a software
# renderer, 16 on others) in the stats' sum; the same rays, no ray type
# walking more tiles and fewer tiles in all (work counters).
expect_rc 0 "bucket masks" -- -o "$out/bm.exr" -W 32 -H 24 --spp 2 --bucket-masks --count-work --stats "$out/bm.json"
"$exr" --exact "$out/bm.exr" "$out/d.exr" && ok || fail "--bucket-masks changed the image"
expect_rc 0 "bucket masks with sub-tiles, the grid, adaptive buckets" -- -o "$out/bm2.exr" -W 32 -H 24 --spp 2 --bucket-masks --sub-tiles --large-grid --depth-buckets adaptive
"$exr" --exact "$out/bm2.exr" "$out/d.exr" && ok || fail "--bucket-masks --sub-tiles --large-grid --depth-buckets adaptive changed the image"
"$json" "$out/bm.json" \
  'd["bytes_total"] == sum(b["used"] for b in d["buffers"])' \
  'd["bytes"]["bucket masks"] > 0 and d["bytes"]["list heads"] in (8 * d["bytes"]["bucket masks"], 16 * d["bytes"]["bucket masks"])' \
  && ok || fail "bm.json: the masks' bytes"
python3 - "$out/w.json" "$out/bm.json" <<'PY' && ok || fail "--bucket-masks' bytes: the totals differ by other than the masks"
import json, sys
off, on = (json.load(open(p)) for p in sys.argv[1:])
assert on["bytes_total"] - off["bytes_total"] == on["bytes"]["bucket masks"], (off["bytes_total"], on["bytes_total"])
PY
python3 - "$out/w.json" "$out/bm.json" <<'PY' && ok || fail "--bucket-masks' work counts"
import json, sys
off, on = (json.load(open(p))["frames"][0]["work"] for p in sys.argv[1:])
for t in off:
    a, b = off[t], on[t]
    assert a["rays"] == b["rays"] and b["tiles"] <= a["tiles"], (t, a, b)
assert sum(on[t]["tiles"] for t in on) < sum(off[t]["tiles"] for t in off)
PY
# Node depth ranges (--node-depths): the same image bit for bit, alone and
# with every other trace option and adaptive depth buckets; the build says
# it stored them; no bytes of their own; the same tiles and list nodes read
# on closest-hit rays, no more triangle tests on any of those ray types and
# fewer in all.
expect_rc 0 "node depth ranges" -- -o "$out/nd.exr" -W 32 -H 24 --spp 2 --node-depths --count-work --stats "$out/nd.json"
"$exr" --exact "$out/nd.exr" "$out/d.exr" && ok || fail "--node-depths changed the image"
expect_rc 0 "node depth ranges with every trace option, adaptive buckets" -- -o "$out/nd2.exr" -W 32 -H 24 --spp 2 --node-depths --sub-tiles --bucket-masks --large-grid --depth-buckets adaptive
"$exr" --exact "$out/nd2.exr" "$out/d.exr" && ok || fail "--node-depths with every option changed the image"
python3 - "$out/w.json" "$out/nd.json" <<'PY' && ok || fail "--node-depths' work counts and bytes"
import json, sys
offj, onj = (json.load(open(p)) for p in sys.argv[1:])
assert onj["node_depths"] is True and offj["node_depths"] is False
assert onj["bytes_total"] == offj["bytes_total"], (offj["bytes_total"], onj["bytes_total"])
off, on = offj["frames"][0]["work"], onj["frames"][0]["work"]
for t in off:
    a, b = off[t], on[t]
    assert a["rays"] == b["rays"] and a["tiles"] == b["tiles"], t
    assert t == "visibility" or a["list_nodes"] == b["list_nodes"], t
    assert t == "visibility" or b["triangle_tests"] <= a["triangle_tests"], (t, a, b)
assert sum(on[t]["triangle_tests"] for t in on) < sum(off[t]["triangle_tests"] for t in off)
PY
# The ray sort (--sort-rays): the same image bit for bit, its passes ran, its
# buffers counted (unsorted rays and batch: 36 B per pixel and a 16-byte
# header; scratch: a counter per bucket and a key per pixel).
expect_rc 0 "sorted rays" -- -o "$out/s.exr" -W 32 -H 24 --spp 2 --sort-rays --stats "$out/s.json"
"$exr" --exact "$out/s.exr" "$out/d.exr" && ok || fail "--sort-rays changed the image"
"$json" "$out/s.json" \
  '[p["ms"] > 0 for p in d["passes"] if p["name"] == "ray sort"] == [True]' \
  '[b["used"] for b in d["buffers"] if b["name"] == "pt ray sort"] == [32 * 24 * 40 + 16 + 8192 * 4]' \
  'd["bytes_total"] == sum(b["used"] for b in d["buffers"])' \
  && ok || fail "s.json: the sort's pass and buffers"
"$json" "$out/d.json" '[p["ms"] for p in d["passes"] if p["name"] == "ray sort"] == [0]' \
  '"pt ray sort" not in [b["name"] for b in d["buffers"]]' \
  && ok || fail "d.json: a sort without --sort-rays"
# A DIRT EXR's provenance, and a scene within an explicit budget (the load
# also counts the file it reads and the parsed JSON: this 585-byte glTF needs
# between 32 and 36 KB).
expect_rc 0 "exr with a seed and a budget" -- "$tmp/good.gltf" -o "$out/p.exr" -W 16 -H 16 --spp 3 --seed 9 --max-scene-memory 64K
"$exr" --attrs "$out/p.exr" "${prov[@]}" >"$tmp/attrs" && grep -qx 'dirt.engine=dirt' "$tmp/attrs" &&
  grep -qx "dirt.scene=$tmp/good.gltf" "$tmp/attrs" && grep -qx 'dirt.seed=9' "$tmp/attrs" &&
  grep -qx 'dirt.samples=3' "$tmp/attrs" && grep -q '^dirt.device=OpenGL ' "$tmp/attrs" && ok ||
  { fail "p.exr's provenance"; cat "$tmp/attrs" >&2; }
expect_rc 0 "raster engine" -- --engine raster -o "$out/r.png" -W 32 -H 24
mkdir -p "$out/ads"
expect_rc 0 "debug pictures and graph" -- -o "$out/g.png" -W 32 -H 24 --spp 1 --debug-ads "$out/ads" --graph-dot "$out/pt.dot"
for f in ads_v0_camera_lists.png ads_v0_camera_zmin.png ads_v0_camera_zmax.png ads_v6_nz_lists.png ads_graph.dot; do
  [ -s "$out/ads/$f" ] && ok || fail "--debug-ads did not write $f"
done
head -c 8 "$out/ads/ads_v0_camera_lists.png" | od -An -tx1 | grep -q '89 50 4e 47' && ok || fail "heat map is not a PNG"
grep -q 'fill primitives' "$out/ads/ads_graph.dot" && ok || fail "build graph DOT lacks the fill pass"
grep -q 'shadow trace 1' "$out/pt.dot" && grep -q 'accumulate' "$out/pt.dot" && ok || fail "path tracer DOT lacks its passes"
expect_rc 2 "graph dot with raster engine" -- --engine raster -o "$out/r2.png" --graph-dot "$out/x.dot"
expect_rc 0 "ao, raster fetch, single view" -- -o "$out/ao.png" -W 32 -H 24 --spp 2 --mode ao --ao-distance 0.5 --fetch raster --views single
head -c 4 "$out/d.exr" | od -An -tx1 | grep -q '76 2f 31 01' && ok || fail "d.exr is not an EXR"
[ -s "$out/d.png" ] && ok || fail "no PNG preview beside the EXR"

expect_rc 0 "frame range" -- "$tmp/good.gltf" -o "$out/f_%03d.png" --frames 2:4 -W 16 -H 16 --spp 1
for i in 002 003 004; do [ -s "$out/f_$i.png" ] && ok || fail "frame $i missing"; done
[ ! -e "$out/f_001.png" ] && [ ! -e "$out/f_005.png" ] && ok || fail "frames outside the range written"

# --info: the scene summary, no output needed.
expect_rc 0 "info of the default scene" -- --info
grep -q '^triangles  1478$' "$tmp/stdout" && grep -q '^cameras    1$' "$tmp/stdout" \
  && grep -q '^emitters   2 triangles, 1 emissive material$' "$tmp/stdout" && ok \
  || fail "--info lacks the default scene's counts"
expect_rc 2 "info of a missing scene" -- --info "$tmp/nope.gltf"

# Without -H the height follows the camera's aspect (the default scene's
# camera has none: 4:3, like the automatic camera).
expect_rc 0 "height from the aspect" -- -o "$out/aspect.png" -W 40 --spp 1
python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); sys.exit(struct.unpack(">II", d[16:24]) != (40, 30))' \
  "$out/aspect.png" && ok || fail "aspect.png is not 40x30"

expect_rc 0 "missing texture only warns" -- "$tmp/notex.gltf" -o "$out/notex.png" -W 16 -H 16 --spp 1
grep -qi "missing.png" "$tmp/stderr" && ok || fail "no warning naming the missing texture"

ls "$out" | grep -q '\.tmp' && fail "temporary files left: $(ls "$out")" || ok
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
