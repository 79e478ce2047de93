#!/bin/bash
# armctl jog in a real terminal (tmux): raw keys as a person types them, on the embedded
# emulated xArm. '2' picks joint 2, 'w' held (repeated as a held key repeats) turns it, space
# stops, Esc ends the session with the arm at rest; the screen shows the help, the status line
# and where the tool came to rest. Waits poll for what the screen shows (no fixed settling).
set -euo pipefail
armctl=$1
sock="armctl-jog-test-$$"
tm() { tmux -L "$sock" "$@"; }
trap 'tm kill-server 2>/dev/null || true' EXIT

screen() { tm capture-pane -p -t jog -S -50 2>/dev/null || true; }
wait_for() {  # wait_for TEXT: up to 60 s for TEXT on the screen
  for _ in $(seq 600); do
    if screen | grep -qF -- "$1"; then return 0; fi
    sleep 0.1
  done
  echo "FAIL: '$1' never showed; the screen:"; screen; exit 1
}

tm new-session -d -s jog -x 200 -y 40 "ASAN_OPTIONS=detect_leaks=0 $armctl jog --arm xarm; echo jog-exit=\$?; sleep 600"
wait_for "keys: w/s x+/-"
wait_for "tool moves in the base frame at 25 mm/s"
start_line=$(screen | grep -o 'x *[-0-9.]* *y *[-0-9.]* *z *[-0-9.]* mm' | tail -1)
tm send-keys -t jog 2
wait_for "joint 2 (servo5) at 25 % of its velocity limit"
# Held for a second: a first press, then repeats some 30 times a second.
for _ in $(seq 30); do tm send-keys -t jog w; sleep 0.033; done
tm send-keys -t jog Space
wait_for "stop"
tm send-keys -t jog Escape
wait_for "jog-exit="
screen | grep -qF "jog-exit=0" || { echo "FAIL: armctl jog did not exit 0"; screen; exit 1; }
rest=$(screen | grep -o 'at rest at x [-0-9.]* y [-0-9.]* z [-0-9.]* mm' | tail -1)
[ -n "$rest" ] || { echo "FAIL: no 'at rest at' line"; screen; exit 1; }
z=$(echo "$rest" | awk '{print $9}')
# From the top (z 366 mm, the arm upright) the shoulder turned for about a second at 25 % of
# its velocity limit: the tool came down by many millimetres.
awk -v z="$z" 'BEGIN { exit !(z < 350) }' || { echo "FAIL: the tool stayed at z $z mm (start: $start_line)"; screen; exit 1; }
echo "jog under tmux: started at '$start_line', $rest"
