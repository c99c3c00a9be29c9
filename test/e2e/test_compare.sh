#!/usr/bin/env bash
# dirt-compare as a user runs it: bad input exits 2 up front with a one-line
# reason; a sweep on the default scene (2 sizes x 2 MMRT thicknesses) and on
# the shared Cornell box writes every output (checked by compare_check.py
# against doc/compare.md's schema, plots read back); a rerun with the same DIR
# measures nothing and rewrites the same rows; the bytes per buffer of a row
# equal what dirt-render --stats reports for the same settings (DIRT and
# MMRT); a configuration that fails mid-sweep (an A-buffer beyond what the
# GPU holds in one array, known only once built) is recorded as failed with
# its reason, the configurations after it are measured, and the exit status is 1;
# --no-quality leaves out only the agreement plot.
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
[ -e "$tmp/o1" ] && [ -n "$(ls -A "$tmp/o1")" ] && fail "files left in o1"
"$cmp" --help | grep -q -- '--thickness LIST' || fail "--help"

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
out=$tmp/out
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
    python3 - "$out/results.json" "$r" "$e" >"$tmp/render_args" <<'PY'
import json, sys
row = json.load(open(sys.argv[1]))["configurations"][int(sys.argv[2])]
s, e = row["settings"], sys.argv[3]
a = [] if row["scene"]["path"] == "default" else [row["scene"]["path"]]
a += ["-W", s["width"], "-H", s["height"], "--views", s["views"], "-t", s["time"],
      "--spp", s["spp"], "--bounces", s["bounces"], "--seed", s["seed"],
      "--background", "1,1,1", "--engine", e]
if s["face_size"]:
    a += ["--face-size", s["face_size"]]
if e == "dirt":
    a += ["-S", s["dirt_tile_size"], "-B", s["dirt_buckets"]]
else:
    a += ["-B", s["mmrt_buckets"], "--march", s["mmrt_march"],
          "--thickness", repr(s["mmrt_thickness"])]
print("\n".join(str(x) for x in a))
PY
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
# --no-quality: no agreement figures, so no agreement plot; the others are made.
if "$cmp" default -o "$tmp/nq" --res 32x16 --repeat 1 --warmup 0 --no-quality -q \
    >"$tmp/nq.log" 2>&1; then
  for p in memory_vs_resolution time_vs_resolution ratios_per_scene; do
    [ -s "$tmp/nq/$p.png" ] || fail "--no-quality: no $p.png"
  done
  [ -e "$tmp/nq/agreement_vs_thickness.png" ] && fail "--no-quality drew an empty agreement plot"
else
  fail "--no-quality run: exit $?"; cat "$tmp/nq.log" >&2
fi
[ "$fails" -eq 0 ] && echo "test_compare: all checks passed"
[ "$fails" -eq 0 ]
