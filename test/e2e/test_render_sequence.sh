#!/usr/bin/env bash
# dirt-render frame sequences as a farm uses them: frame lists and # names
# into new directories, JSON Lines logs, kill and resume with
# --skip-existing, two workers sharing a directory with --placeholders,
# shares of a job array, stale temp files, per-frame seeds, reference MSE.
# Frames are compared pixel for pixel (exr_compare --exact): their headers
# differ by the command line and the time that made them.
# usage: test_render_sequence.sh DIRT_RENDER EXR_COMPARE
set -u
render=$1 exr=$2
same() { "$exr" --exact "$1" "$2" >/dev/null; }
json=$(dirname "$0")/json_check.py
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0 fails=0
ok() { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }

scene=${DIRT_SHARED_DIR:-../shared}/scenes/gltf/BoxAnimated/BoxAnimated.gltf
if [ ! -r "$scene" ]; then
  if [ "${CI:-}" = true ]; then echo "FAIL: $scene missing (CI=true)"; echo "0 passed, 1 failed"; exit 1; fi
  echo "no $scene: skipping"; exit 77
fi
small=(-W 24 -H 18 --spp 1 -q)
# frames N LOG: frame numbers of LOG's frame records, sorted, one line.
frames() { python3 -c 'import json,sys; print(" ".join(str(int(json.loads(l)["frame"])) for l in open(sys.argv[1]) if "frame" in json.loads(l)))' "$1" | tr ' ' '\n' | sort -n | tr '\n' ' '; }
count_temps() { find "$1" -name '*.tmp.*' | wc -l; }

# 1. # names into a new directory, a frame list with a step, the JSON Lines log.
"$render" "$scene" -o "$tmp/shot/a/f_####.exr" --frames 0:6:2 "${small[@]}" --log "$tmp/shot/log.jsonl"
rc=$?
if [ $rc -eq 3 ]; then
  [ "${CI:-}" = true ] && { echo "FAIL: no GL context (CI=true)"; echo "0 passed, 1 failed"; exit 1; }
  echo "no OpenGL context: skipping"; exit 77
fi
[ $rc -eq 0 ] && ok || fail "step sequence exit $rc"
for f in 0000 0002 0004 0006; do [ -s "$tmp/shot/a/f_$f.exr" ] && ok || fail "f_$f.exr missing"; done
[ ! -e "$tmp/shot/a/f_0001.exr" ] && ok || fail "frame 1 rendered with step 2"
[ "$(frames "$tmp/shot/log.jsonl")" = "0 2 4 6 " ] && ok || fail "log frames: $(frames "$tmp/shot/log.jsonl")"
python3 - "$tmp/shot/log.jsonl" <<'PY' && ok || fail "JSON Lines records"
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
recs, summary = lines[:-1], lines[-1]["summary"]
assert summary == {**summary, "frames": 4, "rendered": 4, "skipped": 0}, summary
for r in recs:
    assert r["file"].endswith("f_%04d.exr" % r["frame"]), r["file"]
    assert abs(r["time"] - r["frame"] / 24) < 1e-9 and r["seed"] == 0
    assert r["rays"] > 0 and r["bytes_total"] > 0 and len(r["camera"]["eye"]) == 3
    assert all(p["clock"] in ("gpu", "cpu") for p in r["passes"])
PY

# 2. Lists and printf names.
"$render" "$scene" -o "$tmp/list/f_%03d.png" --frames 5,1,3-4,3 "${small[@]}" && ok || fail "list exit"
[ "$(ls "$tmp/list" | tr '\n' ' ')" = "f_001.png f_003.png f_004.png f_005.png " ] && ok \
  || fail "list files: $(ls "$tmp/list" | tr '\n' ' ')"

# 3. Kill mid-sequence (SIGTERM): no temp file survives; --skip-existing
#    renders exactly the missing frames, equal to a one-process render.
"$render" "$scene" -o "$tmp/one/f_##.exr" --frames 0:7 "${small[@]}" || fail "reference sequence"
"$render" "$scene" -o "$tmp/kill/f_##.exr" --frames 0:7 -W 24 -H 18 --spp 64 -q &
pid=$!
for _ in $(seq 1 600); do
  [ "$(ls "$tmp/kill" 2>/dev/null | grep -c '\.exr$')" -ge 2 ] && break
  sleep 0.1
done
kill -TERM $pid; wait $pid; rc=$?
[ $rc -eq 143 ] && ok || fail "killed worker exit $rc (want 143: SIGTERM)"
[ "$(count_temps "$tmp/kill")" -eq 0 ] && ok || fail "temp files after SIGTERM: $(ls "$tmp/kill")"
done_before=$(ls "$tmp/kill" | grep -c '\.exr$')
"$render" "$scene" -o "$tmp/kill/f_##.exr" --frames 0:7 -W 24 -H 18 --spp 64 -q --skip-existing \
  --log "$tmp/kill/log.jsonl" && ok || fail "resume exit"
rendered=$(python3 -c 'import json,sys; print(json.loads(open(sys.argv[1]).readlines()[-1])["summary"]["rendered"])' "$tmp/kill/log.jsonl")
[ "$rendered" -eq $((8 - done_before)) ] && ok || fail "resume rendered $rendered, $done_before were done"
# The 64-spp frames differ from the 1-spp ones; render the same settings once
# in one process and compare every frame.
"$render" "$scene" -o "$tmp/one64/f_##.exr" --frames 0:7 -W 24 -H 18 --spp 64 -q || fail "one-process 64"
for i in 00 01 02 03 04 05 06 07; do
  same "$tmp/kill/f_$i.exr" "$tmp/one64/f_$i.exr" && ok || fail "resumed frame $i differs"
done

# 4. Two workers on one directory with --placeholders: every frame once.
"$render" "$scene" -o "$tmp/farm/f_##.exr" --frames 0:11 "${small[@]}" --placeholders \
  --log "$tmp/w1.jsonl" & p1=$!
"$render" "$scene" -o "$tmp/farm/f_##.exr" --frames 0:11 "${small[@]}" --placeholders \
  --log "$tmp/w2.jsonl" & p2=$!
wait $p1 && wait $p2 && ok || fail "placeholder workers failed"
all=$( (frames "$tmp/w1.jsonl"; frames "$tmp/w2.jsonl") | tr ' ' '\n' | grep . | sort -n | tr '\n' ' ')
[ "$all" = "0 1 2 3 4 5 6 7 8 9 10 11 " ] && ok || fail "frames rendered by the two workers: $all"
[ "$(ls "$tmp/farm" | grep -c claim)" -eq 0 ] && ok || fail "claims left: $(ls "$tmp/farm")"
# A stale claim (its worker died long ago) is taken over.
: >"$tmp/farm/f_12.exr.claim.0"
touch -d '2 hours ago' "$tmp/farm/f_12.exr.claim.0"
: >"$tmp/farm/f_13.exr.claim.0" # fresh: another worker's
"$render" "$scene" -o "$tmp/farm/f_##.exr" --frames 12:13 "${small[@]}" --placeholders \
  --log "$tmp/w3.jsonl" && ok || fail "takeover exit"
[ "$(frames "$tmp/w3.jsonl")" = "12 " ] && ok || fail "takeover rendered: $(frames "$tmp/w3.jsonl")"
[ -s "$tmp/farm/f_12.exr" ] && [ ! -e "$tmp/farm/f_13.exr" ] && ok || fail "claims not honoured"

# 5. Stale temp files: a dead writer's are removed, a live one's stay.
host=$(hostname | tr './' '--' | cut -c1-64)
: >"$tmp/farm/f_00.exr.tmp.$host.999999.dead00"
: >"$tmp/farm/f_00.exr.tmp.$host.$$.live00"
"$render" "$scene" -o "$tmp/farm/f_##.exr" --frames 0:1 "${small[@]}" --skip-existing || fail "clean run"
[ ! -e "$tmp/farm/f_00.exr.tmp.$host.999999.dead00" ] && ok || fail "dead writer's temp file kept"
[ -e "$tmp/farm/f_00.exr.tmp.$host.$$.live00" ] && ok || fail "live writer's temp file removed"

# 6. Shares of a job array: --chunk K/N and Slurm's variables.
"$render" "$scene" -o "$tmp/chunk/f_##.exr" --frames 0:5 "${small[@]}" --chunk 2/3 || fail "chunk"
[ "$(ls "$tmp/chunk" | tr '\n' ' ')" = "f_02.exr f_03.exr " ] && ok || fail "chunk 2/3: $(ls "$tmp/chunk")"
SLURM_ARRAY_TASK_ID=7 SLURM_ARRAY_TASK_MIN=5 SLURM_ARRAY_TASK_COUNT=3 \
  "$render" "$scene" -o "$tmp/slurm/f_##.exr" --frames 0:5 "${small[@]}" --chunk slurm || fail "slurm chunk"
[ "$(ls "$tmp/slurm" | tr '\n' ' ')" = "f_04.exr f_05.exr " ] && ok || fail "slurm share: $(ls "$tmp/slurm")"

# 7. Noise over time: the same seed on every frame of a still scene, unless
#    --animated-seed (its seeds are in the log).
"$render" -o "$tmp/seed/s_#.exr" --frames 0:1 "${small[@]}" || fail "still frames"
same "$tmp/seed/s_0.exr" "$tmp/seed/s_1.exr" && ok || fail "a still scene's frames differ"
"$render" -o "$tmp/seed/a_#.exr" --frames 0:1 "${small[@]}" --animated-seed --log "$tmp/seed.jsonl" \
  || fail "animated seed"
same "$tmp/seed/a_0.exr" "$tmp/seed/a_1.exr" && fail "--animated-seed frames are equal" || ok
python3 -c 'import json,sys; s=[json.loads(l)["seed"] for l in open(sys.argv[1]) if "seed" in l]; sys.exit(len(set(s)) != 2)' \
  "$tmp/seed.jsonl" && ok || fail "per-frame seeds not recorded"

# 8. --mse-reference: zero against itself, positive against other noise.
"$render" -o "$tmp/ref.exr" "${small[@]}" --seed 4 || fail "reference"
"$render" -o "$tmp/same.exr" -W 24 -H 18 --spp 1 --seed 4 --mse-reference "$tmp/ref.exr" \
  --log "$tmp/mse.jsonl" 2>"$tmp/mse.err" || fail "mse run"
grep -q 'MSE 0, relative MSE 0' "$tmp/mse.err" && ok || fail "self MSE not 0: $(cat "$tmp/mse.err")"
"$render" -o "$tmp/other.exr" -W 24 -H 18 --spp 1 --seed 5 --mse-reference "$tmp/ref.exr" \
  --log "$tmp/mse.jsonl" -q || fail "mse run 2"
python3 -c 'import json,sys; r=[json.loads(l) for l in open(sys.argv[1]) if "mse" in l]; sys.exit(not (r[0]["mse"] == 0 and r[1]["mse"] > 0 and r[1]["rel_mse"] > 0))' \
  "$tmp/mse.jsonl" && ok || fail "recorded MSE"

# 9. Say what will go wrong: an unlit scene on black, options that do nothing.
"$render" "$scene" -o "$tmp/warn.exr" -W 16 -H 12 --spp 1 --exposure 1 -t 0.5 --frames 0:0 \
  2>"$tmp/warn.err" >/dev/null || fail "warn run"
grep -q 'the image will be black' "$tmp/warn.err" && ok || fail "no unlit warning: $(cat "$tmp/warn.err")"
grep -q 'warning: --exposure and --tonemap only change PNG output' "$tmp/warn.err" && ok \
  || fail "no --exposure warning"
grep -q 'warning: -t is ignored with --frames' "$tmp/warn.err" && ok || fail "no -t warning"
"$render" "$scene" -o "$tmp/lit.exr" -W 16 -H 12 --spp 1 --background 1,1,1 2>"$tmp/lit.err" >/dev/null
grep -q 'will be black' "$tmp/lit.err" && fail "unlit warning with a background" || ok
# --tonemap changes the PNG, not the EXR.
"$render" -o "$tmp/tm_clamp.png" "${small[@]}" || fail "clamp png"
"$render" -o "$tmp/tm_aces.png" "${small[@]}" --tonemap aces || fail "aces png"
cmp -s "$tmp/tm_clamp.png" "$tmp/tm_aces.png" && fail "--tonemap aces changed nothing" || ok

# 10. One AOV set from dirt, mmrt and embree, read back by OpenImageIO.
if command -v oiiotool >/dev/null; then
  for e in dirt mmrt embree raster; do
    "$render" -o "$tmp/aov_$e.exr" "${small[@]}" --engine $e || fail "aov render $e"
  done
  want="R, G, B, A, Z, ID, N.X, N.Y, N.Z, albedo.R, albedo.G, albedo.B"
  for e in dirt mmrt embree; do
    got=$(oiiotool --info -v "$tmp/aov_$e.exr" | sed -n 's/^ *channel list: //p')
    [ "$got" = "$want" ] && ok || fail "$e channels: $got"
  done
  got=$(oiiotool --info -v "$tmp/aov_raster.exr" | sed -n 's/^ *channel list: //p')
  [ "$got" = "R, G, B, A, Z, N.X, N.Y, N.Z" ] && ok || fail "raster channels: $got"
  # DIRT's Z as OpenImageIO reads it equals Embree's (same seed, same frame).
  oiiotool "$tmp/aov_dirt.exr" --ch Z -o "$tmp/zd.exr" && oiiotool "$tmp/aov_embree.exr" --ch Z -o "$tmp/ze.exr" \
    && oiiotool --fail 1e-5 --diff "$tmp/zd.exr" "$tmp/ze.exr" >/dev/null && ok || fail "DIRT Z != Embree Z"
elif [ "${CI:-}" = true ]; then
  fail "no oiiotool (CI=true: apt-get install openimageio-tools)"
else
  echo "no oiiotool: AOV read-back check skipped" >&2
fi

[ "$(count_temps "$tmp")" -eq 1 ] && ok || fail "temp files left: $(find "$tmp" -name '*.tmp.*')"
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
