#!/bin/sh
# view_xvfb_test.sh — frontsteal-view tested for real (ctest render.view_xvfb): under its own Xvfb, input through
# xdotool (XTEST, as a user's keyboard and mouse), the viewer's screenshot against the headless EGL render of the camera it
# printed (view_reference: silhouette IoU >= 0.97, as greedy_renderer_test), two negative controls that must fail
# the same check (the camera before the input, and the view turned 40 degrees), and the exit paths: WM_DELETE_WINDOW
# (a window manager's close button) -> 0, Escape -> 0, SIGINT -> 0, no DISPLAY or one with no server -> 3, an
# unknown flag -> 2; and the first impression: the overlay opens small, its key list folded until K.
#
# usage: view_xvfb_test.sh FRONTSTEAL_VIEW VIEW_REFERENCE X11_CLOSE_WINDOW WORK_DIR
set -u
view=$1 reference=$2 close_window=$3 work=$4
rm -rf "$work" && mkdir -p "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# --- without a display: exit 3 with a message; a bad flag: exit 2 -------------------------------------------------
env -u DISPLAY -u WAYLAND_DISPLAY "$view" --frames 1 > "$work/nodisplay.out" 2>&1
rc=$?
[ $rc -eq 3 ] && grep -q "no display" "$work/nodisplay.out" && pass "no DISPLAY: exit 3" || { cat "$work/nodisplay.out"; fail "no DISPLAY: exit $rc, want 3"; }
"$view" --no-such-flag > "$work/badflag.out" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q "no-such-flag" "$work/badflag.out" && pass "bad flag: exit 2" || fail "bad flag: exit $rc, want 2"

# --- our own Xvfb on a free display number (-displayfd), always killed ------------------------------------------
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3> "$work/display" 2> "$work/xvfb.log" &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; wait $xvfb 2>/dev/null' EXIT
i=0
while [ ! -s "$work/display" ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
[ -s "$work/display" ] || { cat "$work/xvfb.log"; echo "FAIL: Xvfb did not start"; exit 1; }
DISPLAY=":$(head -n 1 "$work/display")"
export DISPLAY
echo "Xvfb on $DISPLAY"

# A DISPLAY that names no server: GLFW cannot start, exit 3 with a message.
DISPLAY=":$(( $(head -n 1 "$work/display") + 1000 ))" "$view" --frames 1 > "$work/nodisplay2.out" 2>&1
rc=$?
[ $rc -eq 3 ] && grep -q "no display: GLFW could not start" "$work/nodisplay2.out" && pass "unreachable DISPLAY: exit 3" \
  || { cat "$work/nodisplay2.out"; fail "unreachable DISPLAY: exit $rc, want 3"; }

# Starts the viewer in the background (pid in $pid) and waits for its window (id in $wid).
start_viewer() {  # $1: output stem, rest: flags
  stem=$1; shift
  "$view" --scene teapot --size "${view_size:-320x240}" --tessellators 1 --rate 30 "$@" > "$work/$stem.out" 2>&1 &
  pid=$!
  wid=$(timeout 60 xdotool search --sync --onlyvisible --name '^frontsteal-view$' | head -n 1)
  [ -n "$wid" ] || { cat "$work/$stem.out"; fail "$stem: no window"; kill -KILL "$pid" 2>/dev/null; wait "$pid"; return 1; }
}
# Waits (at most 90 s) for the viewer to exit; its status in $rc.
wait_exit() {
  i=0
  while kill -0 "$pid" 2>/dev/null && [ $i -lt 900 ]; do sleep 0.1; i=$((i + 1)); done
  if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid"; fi
  wait "$pid"
  rc=$?
}

# --- 1. input, screenshot, silhouette against the headless render; close like a window manager ----------------
if start_viewer keys --no-overlay --screenshot "$work/view.png"; then
  xdotool windowfocus --sync "$wid" 2>/dev/null
  # T: synchronized (the screenshot is then tessellated for its own view); the wheel up once and Z: zoom in two
  # steps; a left-button drag 40 pixels to the right: orbit 12 degrees; W, D: walk.
  xdotool key t
  xdotool mousemove --window "$wid" 100 100 click 4
  xdotool mousedown 1 mousemove_relative 20 0 mousemove_relative 20 0 mouseup 1
  xdotool key --delay 50 z w d
  xdotool key p
  i=0
  while ! grep -q "screenshot" "$work/keys.out" && [ $i -lt 600 ]; do sleep 0.1; i=$((i + 1)); done
  "$close_window" "$wid" || fail "could not send WM_DELETE_WINDOW"
  wait_exit
  cat "$work/keys.out"
  [ $rc -eq 0 ] && grep -q "window closed" "$work/keys.out" && pass "window close (WM_DELETE_WINDOW): exit 0" || fail "window close: exit $rc, want 0"
  line=$(grep "screenshot" "$work/keys.out" | head -n 1)
  start=$(grep "start camera" "$work/keys.out" | head -n 1 | sed 's/.*start camera //')
  if [ -z "$line" ] || [ ! -s "$work/view.png" ]; then
    fail "no screenshot"
  else
    echo "$line" | grep -q "mode=synchronized" && pass "T synchronized" || fail "T did not synchronize: $line"
    camera=$(echo "$line" | sed 's/.* camera //; s/ mode=.*//')
    [ "$(echo "$camera" | sed 's/ tolerance=.*//')" != "$start" ] && pass "input moved the camera" || fail "the camera did not move"
    # shellcheck disable=SC2086  # the camera is key=value words on purpose
    "$reference" teapot "$work/view.png" 0.97 $camera out="$work/reference.png" && pass "screenshot matches the headless render" \
      || fail "screenshot does not match the headless render of its camera"
    # Negative controls: the same check against other views must fail.
    # shellcheck disable=SC2086
    if "$reference" teapot "$work/view.png" 0.97 $start tolerance=1 out="$work/control-start.png"; then
      fail "negative control passed: the camera before the input"
    else pass "negative control (camera before the input) fails the check"; fi
    # shellcheck disable=SC2086
    if "$reference" teapot "$work/view.png" 0.97 $camera rotate=40 out="$work/control-rotated.png"; then
      fail "negative control passed: the view turned 40 degrees"
    else pass "negative control (view turned 40 degrees) fails the check"; fi
  fi
fi

# --- 2. First impression: at the default 960x600 the overlay opens with the figures and one line of keys; K shows
# the key list. Measured by the overlay's own size on each screenshot line; the shown list is the control that the
# measure sees a key table over the scene (it must cover far more).
view_size=960x600
if start_viewer overlay --screenshot "$work/overlay.png"; then
  view_size=
  xdotool windowfocus --sync "$wid" 2>/dev/null
  sleep 1
  xdotool key p
  i=0
  while [ "$(grep -c "screenshot" "$work/overlay.out")" -lt 1 ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
  xdotool key k
  sleep 1
  xdotool key p
  i=0
  while [ "$(grep -c "screenshot" "$work/overlay.out")" -lt 2 ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
  xdotool key Escape
  wait_exit
  area() { grep "screenshot" "$work/overlay.out" | sed -n "$1p" | sed 's/.*overlay_px=\([0-9]*\)x\([0-9]*\) keys=\([a-z]*\).*/\1 \2 \3/'; }
  set -- $(area 1) $(area 2)
  if [ $# -ne 6 ]; then
    cat "$work/overlay.out"; fail "overlay: no size on the screenshot lines"
  else
    folded=$(( $1 * $2 * 100 / (960 * 600) )) shown=$(( $4 * $5 * 100 / (960 * 600) ))
    echo "overlay at start: $1x$2 px ($folded % of the window, keys $3); after K: $4x$5 px ($shown %, keys $6)"
    [ "$3" = folded ] && [ "$folded" -le 25 ] && pass "overlay at start: figures and one line of keys, $folded % of the window" \
      || fail "overlay at start covers $folded % (keys $3), want at most 25 % with the keys folded"
    [ "$6" = shown ] && [ "$shown" -ge 35 ] && pass "control: K shows the key list, $shown % of the window" \
      || fail "control: after K the overlay covers $shown % (keys $6), want at least 35 %"
  fi
fi
view_size=

# --- 3. Escape -------------------------------------------------------------------------------------------------
if start_viewer escape; then
  xdotool windowfocus --sync "$wid" 2>/dev/null
  xdotool key Escape
  wait_exit
  [ $rc -eq 0 ] && grep -q "window closed" "$work/escape.out" && pass "Escape: exit 0" || { cat "$work/escape.out"; fail "Escape: exit $rc, want 0"; }
fi

# --- 4. Ctrl-C (SIGINT) ----------------------------------------------------------------------------------------
if start_viewer sigint; then
  kill -INT "$pid"
  wait_exit
  [ $rc -eq 0 ] && grep -q "interrupted" "$work/sigint.out" && pass "SIGINT: exit 0" || { cat "$work/sigint.out"; fail "SIGINT: exit $rc, want 0"; }
fi

echo "$failures failure(s)"
[ $failures -eq 0 ]
