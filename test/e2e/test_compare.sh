#!/usr/bin/env bash
# dirt-compare as a user runs it: bad input exits 2 up front with a one-line
# reason; a sweep on the default scene (2 sizes x 2 MMRT thicknesses) and on
# the shared Cornell box writes every output (checked by compare_check.py
# against doc/compare.md's schema and the rows: the memory table without
# repeats, the figures' data per facet and series with their bars and parity
# line, the figures read back); a rerun with the same DIR
# measures nothing and rewrites the same rows; the bytes per buffer of a row
# equal what dirt-render --stats reports for the same settings (DIRT and
# MMRT); a configuration that fails mid-sweep (an A-buffer beyond what the
# GPU holds in one array, known only once built) is recorded as failed with its
# reason, the configurations after it are measured, and the exit status is 1;
# --no-quality leaves out only the agreement plot; each scene is lit as
# authored (its emitters and punctual lights), a scene without light by the
# built-in sky, every scene by --background or --env when given, and each
# row's Embree image is dirt-render's with the same settings and lighting.
#   test_compare.sh PATH/TO/dirt-compare PATH/TO/doc/compare.md PATH/TO/dirt-render
set -u
cmp=$1 doc=$2 render=$3
check=$(dirname "$0")/compare_check.py
tmp=$(mktemp -d /tmp/dirt-e2e-compare-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }

expect2() {
  local what=$1; shift
  "$cmp" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  [ "$rc" -eq 3 ] && { echo "no OpenGL 4.5 context: skipped"; exit 77; }
  if [ "$rc" -ne 2 ]; then fail "$what: exit $rc, want 2"; cat "$tmp/stderr" >&2; return; fi
  tail -n 1 "$tmp/stderr" | grep -q '^dirt-compare: ' || fail "$what: no one-line reason"
}
echo '{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 99, "uri": "nope.bin"}]' \
  >"$tmp/bad.gltf"
touch "$tmp/afile"
expect2 "missing scene" "$tmp/none.glb" -o "$tmp/o1"
expect2 "malformed scene" "$tmp/bad.gltf" -o "$tmp/o1"
expect2 "DIR is a file" default -o "$tmp/afile"
expect2 "DIR not writable" default -o /proc/dirt-compare
expect2 "impossible size" default -o "$tmp/o1" --res 16384x16384
expect2 "bad list" default -o "$tmp/o1" --res 64x
expect2 "bad views" default -o "$tmp/o1" --views sideways
expect2 "no DIR" default
expect2 "--env and --background" default -o "$tmp/o1" --env sky --background 1,1,1
expect2 "--env-intensity without --env" default -o "$tmp/o1" --env-intensity 2
expect2 "missing --env map" default -o "$tmp/o1" --env "$tmp/none.exr"
expect2 "bad --background" default -o "$tmp/o1" --background 1,1
[ -e "$tmp/o1" ] && [ -n "$(ls -A "$tmp/o1")" ] && fail "files left in o1"
"$cmp" --help | grep -q -- '--thickness T,\.\.\.' || fail "--help"
"$cmp" --version >"$tmp/stdout" 2>&1; rc=$?
{ [ $rc -eq 0 ] || [ $rc -eq 3 ]; } && grep -Eq '^dirt-compare [0-9]+\.[0-9]+\.[0-9]+ \(commit ' "$tmp/stdout" ||
  fail "--version: exit $rc"
expect2 "bad tile size" default -o "$tmp/o1" --tile 1,3
"$cmp" --help | grep -q -- '--env FILE' || fail "--help: no --env"

# dirt-render's arguments for row I of a results.json and ENGINE: the same
# settings and lighting (lighting.source: the scene's own lights alone, the
# built-in sky as fallback, or the --env / --background given).
cat >"$tmp/render_args.py" <<'PY'
import json, sys
row = json.load(open(sys.argv[1]))["configurations"][int(sys.argv[2])]
s, e, L = row["settings"], sys.argv[3], row["lighting"]
a = [] if row["scene"]["path"] == "default" else [row["scene"]["path"]]
a += ["-W", s["width"], "-H", s["height"], "--views", s["views"], "-t", s["time"],
      "--spp", s["spp"], "--bounces", s["bounces"], "--seed", s["seed"], "--engine", e]
if L["source"] == "fallback":
    a += ["--env", "sky"]
elif L["source"] == "--env":
    a += ["--env", L["env"], "--env-intensity", L["env_intensity"],
          "--env-rotation", L["env_rotation"]]
elif L["source"] == "--background":
    a += ["--background", ",".join(str(x) for x in L["background"])]
if s["face_size"]:
    a += ["--face-size", s["face_size"]]
if e == "dirt":
    a += ["-S", s["dirt_tile_size"], "-B", s["dirt_buckets"]]
elif e == "mmrt":
    a += ["-B", s["mmrt_buckets"], "--march", s["mmrt_march"],
          "--thickness", repr(s["mmrt_thickness"])]
print("\n".join(str(x) for x in a))
PY

scenes=(default)
rows=4
shared=${DIRT_SHARED_DIR:-}
cornell=$shared/scenes/cornell/CornellBox.glb
if [ -n "$shared" ] && [ -f "$cornell" ]; then
  scenes+=("$cornell"); rows=8
elif [ "${CI:-}" = true ]; then
  fail "CI=true but the shared scenes ($cornell) are missing"
else
  echo "shared scenes absent: default scene only"
fi
out=$tmp/new/parents/out # folders made as with mkdir -p
args=(--res 32x24,48x32 --thickness-rel 0.002,0.01 --warmup 0 --repeat 2 --agree-res 24x16)
"$cmp" "${scenes[@]}" -o "$out" "${args[@]}" 2>"$tmp/run.log"
rc=$?
[ "$rc" -eq 3 ] && { echo "no OpenGL 4.5 context: skipped"; exit 77; }
[ "$rc" -eq 0 ] || { fail "sweep: exit $rc"; cat "$tmp/run.log" >&2; }
grep -q 'ETA' "$tmp/run.log" || fail "no progress with ETA"
python3 "$check" "$out" "$doc" "$rows" || fail "outputs (compare_check.py)"
cp "$out/results.json" "$tmp/first.json"
"$cmp" "${scenes[@]}" -o "$out" "${args[@]}" 2>"$tmp/rerun.log" || fail "rerun: exit $?"
grep -q "($((0)) measured, $rows from the earlier run" "$tmp/rerun.log" ||
  { fail "rerun measured again"; cat "$tmp/rerun.log" >&2; }
python3 - "$tmp/first.json" "$out/results.json" <<'PY' || fail "rerun changed the rows"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
sys.exit(0 if a == b else 1)
PY
python3 "$check" "$out" "$doc" "$rows" || fail "outputs after the rerun"

# Memory equals dirt-render --stats: the first row (default scene) and, with
# the shared scenes, the last (the Cornell box), both techniques, every
# buffer's used and allocated bytes and the session's totals, exactly.
stats_rows=(0)
[ "$rows" -gt 4 ] && stats_rows+=($((rows - 1)))
for r in "${stats_rows[@]}"; do
  for e in dirt mmrt; do
    python3 "$tmp/render_args.py" "$out/results.json" "$r" "$e" >"$tmp/render_args"
    mapfile -t rargs <"$tmp/render_args"
    "$render" "${rargs[@]}" -o "$tmp/stats_$e.exr" --stats "$tmp/stats_$e.json" -q ||
      { fail "dirt-render ${rargs[*]}: exit $?"; continue; }
    python3 - "$out/results.json" "$r" "$e" "$tmp/stats_$e.json" <<'PY' ||
import json, sys
row = json.load(open(sys.argv[1]))["configurations"][int(sys.argv[2])]
e, st = sys.argv[3], json.load(open(sys.argv[4]))
m = row[e]["memory"]
got = [(b["name"], b["used"], b["allocated"]) for b in m["buffers"]]
want = [(b["name"], b["used"], b["allocated"]) for b in st["buffers"]]
bad = got != want or m["session_used"] != st["bytes_total"] or \
      m["session_allocated"] != st["bytes_allocated"] or not want
if bad:
    print("results.json row %s %s:" % (sys.argv[2], e), got, m["session_used"],
          m["session_allocated"], file=sys.stderr)
    print("dirt-render --stats:", want, st["bytes_total"], st["bytes_allocated"],
          file=sys.stderr)
sys.exit(1 if bad else 0)
PY
      fail "row $r $e: bytes per buffer differ from dirt-render --stats"
  done
done

# Lighting. Each scene as authored: the Cornell box (the default scene
# without the shared scenes) by its emissive ceiling, a generated room by its
# point light, and a generated scene without light by the built-in sky; then
# --background and --env for every scene. Each row records its lighting, the
# table states it per scene, a rerun with other lighting measures every row
# again (its id holds the lighting), and the Embree reference of every row is
# byte for byte dirt-render's image of the same settings and lighting.
lit=default
[ "$rows" -gt 4 ] && lit=$cornell
python3 - "$tmp" <<'PY'
import base64, json, struct, sys
floor = [-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2]
wall = [-2, 0, -2, 2, 0, -2, 2, 3, -2, -2, 3, -2]
pos = floor + wall
idx = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7]
pb = struct.pack("<%df" % len(pos), *pos)
ib = struct.pack("<%dH" % len(idx), *idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(pb + ib).decode()
for name, light in (("point", True), ("unlit", False)):
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
         "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 1.5, 5]}],
         "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1}}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
         "buffers": [{"byteLength": len(pb) + len(ib), "uri": uri}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pb)},
                         {"buffer": 0, "byteOffset": len(pb), "byteLength": len(ib)}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                        "min": [-2, 0, -2], "max": [2, 3, 2]},
                       {"bufferView": 1, "componentType": 5123, "count": 12,
                        "type": "SCALAR"}]}
    if light:
        g["extensionsUsed"] = ["KHR_lights_punctual"]
        g["scenes"][0]["nodes"].append(2)
        g["nodes"].append({"translation": [0.5, 2, 0.5],
                           "extensions": {"KHR_lights_punctual": {"light": 0}}})
        g["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 20, "color": [1, 0.9, 0.8]}]}}
    json.dump(g, open("%s/%s.gltf" % (sys.argv[1], name), "w"))
PY
lscenes=("$lit" "$tmp/point.gltf" "$tmp/unlit.gltf")
largs=(--res 40x30 --views single --warmup 0 --repeat 1 --agree-res 8x6 --images)
lighting_run() { # WHAT EXPECTED_SOURCES OPTIONS...: checks one run into $tmp/lit
  local what=$1 want=$2; shift 2
  "$cmp" "${lscenes[@]}" -o "$tmp/lit" "${largs[@]}" "$@" 2>"$tmp/lit.log" ||
    { fail "lighting $what: exit $?"; cat "$tmp/lit.log" >&2; return; }
  python3 - "$tmp/lit" "$want" "$what" <<'PY' || fail "lighting $what: rows or table"
import json, sys
d, want, what = sys.argv[1], sys.argv[2].split(","), sys.argv[3]
rows = json.load(open(d + "/results.json"))["configurations"]
table = open(d + "/table.md").read()
bad = []
own = [(2, 0), (0, 1), (0, 0)] # emissive triangles, punctual lights per scene
env = {"scene": "none", "fallback": "sky", "--background": "background", "--env": "sky"}
for r, w, (e, p) in zip(rows, want, own):
    L = r["lighting"]
    if (L["source"], L["environment"], L["emitter_triangles"], L["punctual_lights"]) != \
            (w, env[w], e, p):
        bad.append("%s: %s" % (r["scene"]["name"], L))
    if "- %s: %s\n" % (r["scene"]["name"], L["summary"]) not in table:
        bad.append("table.md does not state the lighting of " + r["scene"]["name"])
if len(rows) != 3:
    bad.append("%d rows" % len(rows))
if what == "as authored":
    if "- %s: as authored: its own lights (2 emissive triangles); no environment" % \
            rows[0]["scene"]["name"] not in table or \
            "- point.gltf: as authored: its own lights (1 punctual light)" not in table \
            or "- unlit.gltf: fallback: no light of its own, so the built-in sky" not in table:
        bad.append("table.md: " + table.split("In the layout")[0])
for b in bad:
    print(what + ":", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY
  grep -q "(3 measured, 0 from the earlier run" "$tmp/lit.log" ||
    fail "lighting $what: rows of another lighting were reused"
  # one size and one thickness: the figures over triangles and the ratios
  # only (compare_check.py: no agreement figure of a single point)
  python3 "$check" "$tmp/lit" "$doc" 3 || fail "lighting $what: outputs (compare_check.py)"
  [ -s "$tmp/lit/ratios_per_scene.png" ] || fail "lighting $what: no ratios figure"
  for i in 0 1 2; do
    python3 "$tmp/render_args.py" "$tmp/lit/results.json" $i embree >"$tmp/render_args"
    mapfile -t rargs <"$tmp/render_args"
    "$render" "${rargs[@]}" -o "$tmp/lit_$i.png" -q ||
      { fail "dirt-render ${rargs[*]}: exit $?"; continue; }
    png=$(python3 -c 'import json, sys
print(json.load(open(sys.argv[1]))["configurations"][int(sys.argv[2])]["images"]["embree"])' \
      "$tmp/lit/results.json" $i)
    cmp -s "$tmp/lit_$i.png" "$tmp/lit/$png" ||
      fail "lighting $what: row $i's Embree image is not dirt-render ${rargs[*]}'s"
  done
}
lighting_run "as authored" scene,scene,fallback
cp "$tmp/lit_1.png" "$tmp/authored_1.png"
cp "$tmp/lit/results.json" "$tmp/authored.json"
lighting_run "--background" --background,--background,--background --background 0.3,0.2,0.1
cmp -s "$tmp/lit_1.png" "$tmp/authored_1.png" && fail "--background did not change the image"
# the agreement rays aim at the scene's own light whatever the environment
python3 - "$tmp/authored.json" "$tmp/lit/results.json" <<'PY' ||
import json, sys
a, b = ([(r["dirt"]["agreement"]["fraction"], r["mmrt"]["agreement"]["fraction"])
         for r in json.load(open(p))["configurations"]] for p in sys.argv[1:])
sys.exit(0 if a == b and len(a) == 3 else 1)
PY
  fail "the hit agreement changed with --background"
lighting_run "--env" --env,--env,--env --env sky --env-intensity 0.5 --env-rotation 30

# A configuration that fails mid-sweep. 40 stacked quads filling a camera's
# view: 40 fragments a pixel, so MMRT's data nodes (32 B each) at 512x256
# (5.2 M fragments, 168 MB) pass what the GPU holds in one array with storage
# blocks and texel buffers of 4 MiB (DIRT_MAX_BLOCK_BYTES: 8 parts of 4 MiB,
# gl/split.h), which shows only once the fragments are counted; 64x32 before
# it and 32x16 after it fit. DIRT at tile size 8 stays cheap.
python3 - "$tmp/layers.gltf" <<'PY'
import base64, json, struct, sys
n, pos, idx = 40, [], []
for k in range(n):
    b = len(pos)
    pos += [(-50, -50, -k), (50, -50, -k), (50, 50, -k), (-50, 50, -k)]
    idx += [b, b + 1, b + 2, b, b + 2, b + 3]
pb = b"".join(struct.pack("<3f", *p) for p in pos)
ib = b"".join(struct.pack("<I", i) for i in idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(pb + ib).decode()
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 10]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": len(pb) + len(ib), "uri": uri}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pb)},
                    {"buffer": 0, "byteOffset": len(pb), "byteLength": len(ib)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
                   "min": [-50, -50, 1.0 - n], "max": [50, 50, 0]},
                  {"bufferView": 1, "componentType": 5125, "count": len(idx),
                   "type": "SCALAR"}]}, open(sys.argv[1], "w"))
PY
DIRT_MAX_BLOCK_BYTES=4M \
"$cmp" "$tmp/layers.gltf" -o "$tmp/fails" --res 64x32,512x256,32x16 --views single --tile 8 \
  --warmup 0 --repeat 1 --agree-res 16x8 --images 2>"$tmp/fails.log"
rc=$?
python3 - "$tmp/fails/results.json" "$rc" <<'PY' || { fail "mid-sweep failure"; cat "$tmp/fails.log" >&2; }
import json, sys
rows = json.load(open(sys.argv[1]))["configurations"]
st = [r["status"] for r in rows]
why = rows[1].get("reason") if len(rows) == 3 else None
ok = st == ["ok", "failed", "ok"] and int(sys.argv[2]) == 1 and isinstance(why, str) and \
     why.startswith("mmrt: ") and "more than this GPU holds in one array" in why
# --images: the measured rows name their PNGs (relative to DIR), which exist
d = sys.argv[1].rsplit("/", 1)[0]
for r in rows:
    for e in ("dirt", "mmrt", "embree"):
        p = r.get("images", {}).get(e) if r["status"] == "ok" else None
        if r["status"] == "ok" and not (p and open(d + "/" + p, "rb").read(4) == b"\x89PNG"):
            print("row %s: no %s image" % (r["id"], e), file=sys.stderr)
            ok = False
if not ok:
    print("statuses %s, exit %s, reason %r" % (st, sys.argv[2], why), file=sys.stderr)
sys.exit(0 if ok else 1)
PY
grep -q "configuration 2 failed: mmrt: " "$tmp/fails.log" || fail "no line naming the failed configuration"
grep -q "1 failed)" "$tmp/fails.log" || fail "the summary does not count the failure"
# --no-quality: no agreement figures, so no agreement plot (two thicknesses
# notwithstanding); the others are made.
if "$cmp" default -o "$tmp/nq" --res 32x16,48x24 --thickness-rel 0.002,0.01 --repeat 1 \
    --warmup 0 --no-quality -q >"$tmp/nq.log" 2>&1; then
  for p in memory_vs_resolution time_vs_resolution ratios_per_scene; do
    [ -s "$tmp/nq/$p.png" ] || fail "--no-quality: no $p.png"
  done
  [ -e "$tmp/nq/agreement_vs_thickness.png" ] && fail "--no-quality drew an empty agreement plot"
  # what was not measured is an empty CSV cell (null in the JSON), never nan
  python3 - "$tmp/nq/results.csv" <<'PY' || fail "--no-quality: results.csv has nan/inf cells"
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
bad = [(i, rows[0][j]) for i, r in enumerate(rows[1:], 1) for j, c in enumerate(r)
       if c.strip().lower().lstrip("+-") in ("nan", "inf", "infinity")]
empty = sum(1 for r in rows[1:] for c in r if c == "")
if bad or not empty:
    print("cells %s; %d empty" % (bad[:5], empty), file=sys.stderr)
sys.exit(1 if bad or not empty else 0)
PY
else
  fail "--no-quality run: exit $?"; cat "$tmp/nq.log" >&2
fi
# --count-work: each row's work per ray type for DIRT and MMRT, with
# Embree's over DIRT's rays, and its table in table.md.
if "$cmp" default -o "$tmp/cw" --res 32x24 --repeat 1 --warmup 0 --no-quality --count-work -q \
    >"$tmp/cw.log" 2>&1; then
  python3 - "$tmp/cw" <<'PY' || fail "--count-work: rows or table"
import json, sys
d = sys.argv[1]
rows = json.load(open(d + "/results.json"))["configurations"]
types = {"primary", "visibility", "specular", "glossy", "diffuse"}
ok = len(rows) == 1 and all(
    set(r["dirt"]["work"]) == types and set(r["mmrt"]["work"]) == types and
    all(w["rays"] == 32 * 24 * (t == "primary") or t != "primary"
        for t, w in r["dirt"]["work"].items()) and
    all(w["tiles"] > 0 and w["list_nodes"] > 0 and w["embree"]["bvh_nodes"] > 0
        for w in r["dirt"]["work"].values()) and
    all(w["fragments"] > 0 for w in r["mmrt"]["work"].values()) for r in rows)
table = open(d + "/table.md").read()
ok = ok and "## Work per ray (--count-work)" in table and "| diffuse |" in table
sys.exit(0 if ok else 1)
PY
else
  fail "--count-work run: exit $?"; cat "$tmp/cw.log" >&2
fi
# --bucket-masks: the row says so (settings, "|M1" in its id, so earlier
# rows without it are not reused; "+masks" beside S in Table 2) and DIRT's
# memory holds the masks; the sweep's rows without it have none of these.
if "$cmp" default -o "$tmp/bm" --res 32x24 --repeat 1 --warmup 0 --no-quality --bucket-masks -q \
    >"$tmp/bm.log" 2>&1; then
  python3 - "$tmp/bm/results.json" "$out/results.json" <<'PY' || fail "--bucket-masks: rows"
import json, sys
on, off = (json.load(open(p))["configurations"] for p in sys.argv[1:])
def masks(r):
    return sum(b["used"] for b in r["dirt"]["memory"]["buffers"] if b["name"] == "bucket masks")
ok = len(on) == 1 and all(r["settings"]["dirt_bucket_masks"] and r["id"].endswith("|M1") and
                          masks(r) > 0 for r in on)
ok = ok and all(not r["settings"]["dirt_bucket_masks"] and "|M1" not in r["id"] and
                masks(r) == 0 for r in off)
# Table 2 says so beside S; the sweep's table does not
import os
on_t, off_t = (open(os.path.join(os.path.dirname(p), "table.md")).read() for p in sys.argv[1:])
ok = ok and "| 1 +masks | 4/4 |" in on_t
ok = ok and not any(l.startswith("| ") and "+masks" in l for l in off_t.splitlines())
sys.exit(0 if ok else 1)
PY
else
  fail "--bucket-masks run: exit $?"; cat "$tmp/bm.log" >&2
fi
[ "$fails" -eq 0 ] && echo "test_compare: all checks passed"
[ "$fails" -eq 0 ]
