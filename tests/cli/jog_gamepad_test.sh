#!/bin/bash
# armctl jog --gamepad-replay on the embedded emulated xArm: the recorded Xbox pad
# (tests/jog/recordings/xbox_forward.txt) pushes the tool forward while LB is held, stops it
# when LB is let go and when the pad is unplugged, and the session ends at rest when the
# recording does. Then a recording with a bad line is refused, naming the line and what is
# allowed there, before the arm moves; and --record-gamepad's checks.
set -euo pipefail
armctl=$1
recordings=$2
export ASAN_OPTIONS=detect_leaks=0
fail() { echo "FAIL: $1"; echo "$out"; exit 1; }

out=$("$armctl" jog --arm xarm --gamepad-replay "$recordings/xbox_forward.txt" </dev/null 2>&1) || fail "exit $?"
grep -qF "gamepad 'Microsoft X-Box 360 pad' (Xbox layout): hold LB to move" <<<"$out" || fail "no pad line"
grep -qF "dead-man released" <<<"$out" || fail "no dead-man line"
grep -qF "gamepad lost: stopping" <<<"$out" || fail "no unplug line"
rest=$(grep -o 'at rest at x [-0-9.]* y [-0-9.]* z [-0-9.]* mm' <<<"$out" | tail -1)
[ -n "$rest" ] || fail "no 'at rest at' line"
read -r x y <<<"$(awk '{print $5, $7}' <<<"$rest")"
# From the upright start (x 0): two stretches of about a second at 25 mm/s forward.
awk -v x="$x" -v y="$y" 'BEGIN { exit !(x > 35 && x < 60 && y > -1 && y < 1) }' || fail "the tool came to rest at $rest"

bad=$(mktemp)
trap 'rm -f "$bad"' EXIT
printf 'device pad\naxis ABS_X 0 255\naxis ABS_Y 0 255\n0.5 EV_KEY BTN_TL 7\n' >"$bad"
if out=$("$armctl" jog --arm xarm --gamepad-replay "$bad" </dev/null 2>&1); then fail "a bad recording was taken"; fi
grep -qF "$bad:4:19: found '7'; expected 0 (released), 1 (pressed) or 2 (repeated) for a button" <<<"$out" ||
  fail "not the line's error"
# Recording a pad: only with --gamepad, and to a file that can be written (checked before
# the session, not after it).
if out=$("$armctl" jog --arm xarm --record-gamepad "$bad" </dev/null 2>&1); then fail "--record-gamepad without --gamepad"; fi
grep -qF -- "--record-gamepad requires --gamepad" <<<"$out" || fail "not the option's error"
if out=$("$armctl" jog --arm xarm --gamepad /dev/input/event99 --record-gamepad /nonexistent/pad.txt </dev/null 2>&1); then
  fail "a recording to a missing directory"
fi
grep -qF "/nonexistent" <<<"$out" || fail "the unwritable file not named"
echo "jog --gamepad-replay: $rest"
