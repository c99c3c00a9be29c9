# Sourced by the viewer's tests: skips (77) without xvfb-run, Xvfb and
# xdotool (a failure when CI=true), else starts one Xvfb server for the
# whole test (xdotool talks to it too), exports DISPLAY and sets xvfb_pid
# (the caller's EXIT trap kills it), and defines window_id. $tmp must exist.
for tool in xvfb-run Xvfb xdotool; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    [ "${CI:-}" = true ] && { echo "CI=true: $tool missing is a failure"; exit 1; }
    echo "$tool missing: skipping"; exit 77
  fi
done
xvfb_pid=
for n in $(seq "${XVFB_FIRST:-90}" 160); do
  [ -e /tmp/.X11-unix/X$n ] || [ -e /tmp/.X$n-lock ] && continue
  # -noreset: the server would otherwise reset whenever its last client
  # leaves (every dirt-view run here ends so), and a run that connects
  # during that reset finds no display (seen once in a CI dry run).
  Xvfb :$n -screen 0 1600x1200x24 -nolisten tcp -noreset >"$tmp/xvfb.log" 2>&1 &
  xvfb_pid=$!
  export DISPLAY=:$n
  for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done
  xdotool getmouselocation >/dev/null 2>&1 && break
  kill "$xvfb_pid" 2>/dev/null; xvfb_pid=
done
[ -n "${xvfb_pid:-}" ] || { echo "could not start Xvfb"; exit 1; }

# The viewer's window id, once it is mapped (empty after 10 s).
window_id() {
  local wid=
  for _ in $(seq 100); do
    wid=$(xdotool search --name '^dirt-view' 2>/dev/null | head -n 1)
    [ -n "$wid" ] && break; sleep 0.1
  done
  echo "$wid"
}
