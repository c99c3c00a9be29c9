#!/usr/bin/env bash
# How fast dirt-view answers while the path tracer runs: real X input from
# xdotool (XTEST) under its own Xvfb, the viewer at its default window
# (1280x720, panels shown, default engine and scale) tracing the default
# scene (or SCENE), and the time from each input to the first frame shown
# with its effect, read from the viewer's frame log (test hook
# DIRT_VIEW_FRAME_LOG: wall-clock time after each swap, samples, the part of
# the sample in progress, the buffer, the Settings panel's height, the
# mouse button releases read so far):
#   key     keys 2 and 1 in turn (buffer albedo / beauty)
#   click   a left click on the Settings panel's collapse arrow (its height
#           changes: collapsed / open)
# REPEATS of each, alternating, 0.7 s apart, after WARMUP seconds of
# tracing. Prints a markdown table (median, 90th percentile and max per
# kind), the frame times, the render scale and the sample time the viewer
# reported, with the machine and renderer. Extra arguments go to dirt-view
# (e.g. --slice-ms 60, --scale 1, --engine mmrt).
#   perf/view-latency.sh BUILD_DIR [REPEATS] [WARMUP] [SCENE] [-- VIEW-ARGS...]
set -eu
build=$1 repeats=${2:-20} warmup=${3:-4} scene=${4:-}
shift $(( $# < 4 ? $# : 4 ))
[ "${1:-}" = -- ] && shift
view=$build/src/app/dirt-view
for tool in Xvfb xdotool python3; do
  command -v "$tool" >/dev/null || { echo "perf/view-latency.sh: needs $tool" >&2; exit 2; }
done
tmp=$(mktemp -d /tmp/view-latency-XXXXXX)
xvfb_pid= vpid=
cleanup() {
  [ -n "$vpid" ] && kill "$vpid" 2>/dev/null
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT
# The background children get no descriptor above 2 (under `flock LOCK
# perf/view-latency.sh` an X server left behind would keep the lock).
for n in $(seq 170 230); do
  [ -e /tmp/.X11-unix/X$n ] || [ -e /tmp/.X$n-lock ] && continue
  Xvfb :$n -screen 0 1600x1000x24 -nolisten tcp -noreset >"$tmp/xvfb.log" 2>&1 \
    3>&- 4>&- 5>&- 6>&- 7>&- 8>&- 9>&- &
  xvfb_pid=$!
  export DISPLAY=:$n
  for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done
  xdotool getmouselocation >/dev/null 2>&1 && break
  kill "$xvfb_pid" 2>/dev/null; xvfb_pid=
done
[ -n "$xvfb_pid" ] || { echo "perf/view-latency.sh: could not start Xvfb" >&2; exit 1; }
printf 'wait-file %s\nreport %s\nquit\n' "$tmp/stop" "$tmp/report.json" >"$tmp/script.txt"
# shellcheck disable=SC2086
DIRT_VIEW_FRAME_LOG="$tmp/frames.log" "$view" $scene --spp 1048576 --script "$tmp/script.txt" "$@" \
  >"$tmp/view.out" 2>&1 3>&- 4>&- 5>&- 6>&- 7>&- 8>&- 9>&- &
vpid=$!
python3 - "$tmp" "$repeats" "$warmup" <<'PY' || { cat "$tmp/view.out" >&2; exit 1; }
import json, os, statistics, subprocess, sys, time
tmp, repeats, warmup = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
log = os.path.join(tmp, "frames.log")

def rows():
    try:
        return [l.split() for l in open(log) if l.endswith("\n")]
    except FileNotFoundError:
        return []

def xdo(*args):
    return subprocess.run(["xdotool", *args], capture_output=True, text=True).stdout.strip()

wid = ""
for _ in range(300):
    wid = xdo("search", "--name", "^dirt-view")
    if wid and rows():
        break
    time.sleep(0.1)
if not wid:
    sys.exit("perf/view-latency.sh: no dirt-view window")
wid = wid.split()[0]
time.sleep(warmup)

def wait_for(t0, pred, limit=30.0):
    """Seconds from t0 to the first frame shown after t0 where pred holds."""
    end = time.time() + limit
    while time.time() < end:
        for r in rows():
            if float(r[0]) > t0 and pred(r):
                return float(r[0]) - t0, r
        time.sleep(0.002)
    return None, None

lat = {"key": [], "click": []}
mid = []  # inputs that acted within a sample (the sample in progress before and after)
at_once = []  # clicks shown in the frame that read their release
for i in range(repeats):
    # key: the buffer toggles between albedo (2) and beauty (1)
    xdo("mousemove", "--window", wid, "900", "400")
    want = "albedo" if i % 2 == 0 else "beauty"
    before = rows()[-1]
    t0 = time.time()
    xdo("key", "2" if want == "albedo" else "1")
    dt, r = wait_for(t0, lambda r: r[4] == want)
    lat["key"].append(dt)
    if r:
        mid.append(int(r[2]) == int(before[2]) and float(r[3]) > 0)
    time.sleep(0.7)
    # click: the Settings panel's collapse arrow (top left, 8 px in)
    h0, rel0 = rows()[-1][6], int(rows()[-1][7])
    xdo("mousemove", "--window", wid, "17", "17")
    time.sleep(0.05)
    t0 = time.time()
    xdo("click", "1")
    dt, r = wait_for(t0, lambda r: r[6] != h0)
    lat["click"].append(dt)
    seen = next((r for r in rows() if int(r[7]) > rel0), None)
    at_once.append(bool(seen) and seen[6] != h0)
    time.sleep(0.7)
open(os.path.join(tmp, "stop"), "w").close()
for _ in range(600):
    if os.path.exists(os.path.join(tmp, "report.json")):
        break
    time.sleep(0.1)
time.sleep(0.5)
rep = json.load(open(os.path.join(tmp, "report.json")))
cpu = subprocess.run(["sh", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"],
                     capture_output=True, text=True).stdout.strip()
print("machine: %s (%s, %d cores)" % (os.uname().nodename, cpu, os.cpu_count()))
print("device: %s" % rep["device"])
print("window %s, render %s (scale %s%s), slices of %s ms, last sample %.0f ms, %d samples"
      % (rep["window"], rep["render"], rep["scale"], ", automatic" if rep["scale_auto"] else "",
         rep["slice_ms"], rep["last_sample_ms"], rep["samples"]))
f = rep["frame_ms"]
print("frames: median %.1f ms, min %.1f, max %.1f (the last %d)" % (f["median"], f["min"], f["max"], f["count"]))
print()
print("| input | n | answered | median ms | p90 ms | max ms |")
print("|---|---|---|---|---|---|")
for k, v in lat.items():
    got = sorted(1000 * x for x in v if x is not None)
    if got:
        p90 = got[min(len(got) - 1, int(round(0.9 * (len(got) - 1))))]
        print("| %s | %d | %d | %.0f | %.0f | %.0f |" % (k, len(v), len(got), statistics.median(got), p90, got[-1]))
    else:
        print("| %s | %d | 0 | - | - | - |" % (k, len(v)))
print()
print("keys that acted within the sample in progress: %d of %d" % (sum(mid), len(mid)))
print("clicks shown in the frame that read their release: %d of %d" % (sum(at_once), len(at_once)))
PY
wait "$vpid" || true
vpid=
