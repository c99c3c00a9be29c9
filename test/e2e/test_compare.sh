#!/usr/bin/env bash
# dirt-compare as a user runs it: bad input exits 2 up front with a one-line
# reason; a sweep on the default scene (2 sizes x 2 MMRT thicknesses) and on
# the shared Cornell box writes every output (checked by compare_check.py
# against doc/compare.md's schema, plots read back); a rerun with the same DIR
# measures nothing and rewrites the same rows.
#   test_compare.sh PATH/TO/dirt-compare PATH/TO/doc/compare.md
set -u
cmp=$1 doc=$2
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
[ "$fails" -eq 0 ] && echo "test_compare: all checks passed"
[ "$fails" -eq 0 ]
