#!/usr/bin/env bash
# A drag moves dirt-view's camera by its whole length at any frame rate: in
# a real window under Xvfb, with every frame made 1.5 s slower (the test
# hook DIRT_VIEW_SLOW_FRAME_MS), a real left drag of 50 pixels sent with
# xdotool, press to release within one frame, or spread over several frames,
# leaves the camera where the script's `orbit 15 0` (0.3 degrees a pixel)
# puts it.
#   test_view_drag.sh DIRT-VIEW
set -u
view=$1
tmp=$(mktemp -d /tmp/dirt-view-drag-XXXXXX)
trap 'rm -rf "$tmp"; [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null' EXIT
fails=0 passes=0
ok()   { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
# shellcheck source=view_xvfb.sh
. "$(dirname "$0")/view_xvfb.sh"
args=(--window 160x120 --no-ui --spp 1 --scale 1 -q)

# The script's orbit: where the drags must end.
printf 'orbit 15 0\nwait-frames 1\nreport %s\nquit\n' "$tmp/want.json" >"$tmp/want.txt"
"$view" "${args[@]}" --script "$tmp/want.txt" >"$tmp/want.out" 2>&1 ||
  { fail "orbit run: exit $?"; cat "$tmp/want.out" >&2; }

# drag NAME PAUSE: five 10-pixel moves PAUSE seconds apart, the button down
# throughout.
drag() {
  local name=$1 pause=$2
  rm -f "$tmp/go"
  printf 'wait-file %s\nwait-frames 2\nreport %s\nquit\n' "$tmp/go" "$tmp/$name.json" >"$tmp/$name.txt"
  DIRT_VIEW_SLOW_FRAME_MS=1500 "$view" "${args[@]}" --script "$tmp/$name.txt" \
    >"$tmp/$name.out" 2>&1 &
  local vpid=$! wid=
  wid=$(window_id)
  if [ -z "$wid" ]; then fail "$name: no window"; else
    sleep 2
    xdotool mousemove --window "$wid" 80 60
    sleep 0.2
    xdotool mousedown 1
    for _ in 1 2 3 4 5; do xdotool mousemove_relative -- 10 0; sleep "$pause"; done
    xdotool mouseup 1
  fi
  touch "$tmp/go"
  wait "$vpid" || { fail "$name: exit $?"; cat "$tmp/$name.out" >&2; }
  python3 - "$tmp/want.json" "$tmp/$name.json" <<'PY' && ok || fail "$name: the drag did not orbit 15 degrees"
import json, sys
want, got = (json.load(open(p)) for p in sys.argv[1:3])
ew, eg = want["camera"]["eye"], got["camera"]["eye"]
d = max(abs(a - b) for a, b in zip(ew, eg))
print("camera %s, eye %s, want %s (off by %.3g)" % (got["camera_mode"], eg, ew, d))
sys.exit(0 if got["camera_mode"] == "look" and d <= 1e-4 * max(1.0, max(map(abs, ew))) else 1)
PY
}
drag quick 0.01   # press to release well inside one 1.5 s frame
drag slow 0.5     # over about two frames

echo "test_view_drag: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
