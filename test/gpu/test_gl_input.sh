#!/bin/sh
# Drives test_gl_input with real X events: runs it under a virtual X server
# (xvfb-run) and answers each "STEP <name> [x y]" it prints with xdotool.
#   test_gl_input.sh EXE input|ui
# Skips (77) without xvfb-run or xdotool, except in CI (CI=true), where a
# missing tool is a failure.
set -u
exe=$1 mode=$2

need() {
  command -v "$1" >/dev/null 2>&1 && return 0
  [ "${CI:-}" = true ] && { echo "CI=true: $1 missing is a failure"; exit 1; }
  echo "$1 missing: skipping"; exit 77
}

if [ -z "${DIRT_INPUT_UNDER_XVFB:-}" ]; then
  need xvfb-run
  need xdotool
  DIRT_INPUT_UNDER_XVFB=1 exec xvfb-run -a sh "$0" "$@"
fi

log=$(mktemp)
title="dirt-$mode-test-$$"
"$exe" "$mode" "$title" >"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null; rm -f "$log"' EXIT
failed=0

fail() {
  echo "test_gl_input.sh: $*"
  failed=1
}

# Waits (10 s at most) for a line of the program's output starting with $1.
wait_line() {
  i=0
  while ! grep -q "^$1" "$log"; do
    if ! kill -0 $pid 2>/dev/null; then
      grep -q "^$1" "$log" && return 0
      echo "test_gl_input.sh: the program ended before printing '$1':"
      cat "$log"
      exit 1
    fi
    i=$((i + 1))
    if [ $i -gt 200 ]; then
      echo "test_gl_input.sh: no '$1' from the program within 10 s:"
      cat "$log"
      exit 1
    fi
    sleep 0.05
  done
}

# Waits for "STEP $1" and sets x, y to the coordinates it names (if any).
step() {
  wait_line "STEP $1\\b"
  set -- $(grep "^STEP $1\\b" "$log" | head -n 1)
  x=${3:-} y=${4:-}
}

wait_line READY
wid=$(xdotool search --sync --name "^$title\$" | head -n 1)
[ -n "$wid" ] || { echo "test_gl_input.sh: no window named $title"; cat "$log"; exit 1; }
# Without a window manager the keyboard follows the focus set here.
xdotool windowfocus "$wid"

if [ "$mode" = input ]; then
  step focus
  step move;         xdotool mousemove --window "$wid" 40 30
  step move2;        xdotool mousemove --window "$wid" 50 35
  step press;        xdotool mousedown 1
  step release;      xdotool mouseup 1
  step right;        xdotool click 3
  step double;       xdotool click --repeat 2 --delay 80 1
  step slow;         xdotool click 1; sleep 1; xdotool click 1
  step scroll_up;    xdotool click --repeat 2 --delay 30 4
  step scroll_down;  xdotool click 5
  step w_down;       xdotool keydown w
  step w_up;         xdotool keyup w
  step shift_l_down; xdotool keydown Shift_L
  step shift_r_down; xdotool keydown Shift_R
  step shift_l_up;   xdotool keyup Shift_L
  step shift_r_up;   xdotool keyup Shift_R
  step f1;           xdotool key F1
  step resize;       xdotool windowsize "$wid" 200 150
  step set_size
  step title
  name=$(xdotool getwindowname "$wid")
  [ "$name" = "$title renamed" ] || fail "window name '$name', want '$title renamed'"
  xdotool key F2 # the program waits for it before closing the window
else
  step hover;  xdotool mousemove --window "$wid" "$x" "$y"
  step click;  xdotool mousemove --window "$wid" "$x" "$y" mousedown 1; sleep 0.1; xdotool mouseup 1
  step away;   xdotool mousemove --window "$wid" "$x" "$y"
  step type;   xdotool mousemove --window "$wid" "$x" "$y" click 1; sleep 0.2
               xdotool type --delay 40 dirt
  step after;  xdotool mousemove --window "$wid" "$x" "$y"
fi

wait $pid
rc=$?
cat "$log"
[ $rc -eq 0 ] || fail "the program failed (exit status $rc)"
exit $failed
