#!/bin/bash
# armctl follow end to end on two embedded simulators: an xArm leading the SCARA for a second
# with the session recorded, the recording replayed on the SCARA, and options refused before
# anything moves.
set -euo pipefail
armctl=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=detect_leaks=0

out=$("$armctl" follow --leader xarm --follower scara --duration 1 --record "$work/session.rec" </dev/null)
echo "$out" | grep -q "copies it (tool to tool)" || { echo "FAIL: no start line: $out"; exit 1; }
echo "$out" | grep -q "follower at rest, leader holding" || { echo "FAIL: no end line: $out"; exit 1; }
# Both simulators keep to the wall clock: a SCARA on simulated time would run ahead of the
# leader's reads and find the leader lost.
if echo "$out" | grep -q "leader lost"; then echo "FAIL: the leader was lost: $out"; exit 1; fi
grep -q "^arm scara" "$work/session.rec" || { echo "FAIL: follower recording"; cat "$work/session.rec"; exit 1; }
grep -q "^arm xarm" "$work/session.leader.rec" || { echo "FAIL: leader recording"; exit 1; }
"$armctl" replay "$work/session.rec" --arm scara >/dev/null || { echo "FAIL: replay of the session"; exit 1; }

refused() {  # refused TEXT ARGS...: exits 1 naming TEXT
  local text=$1; shift
  if err=$("$armctl" follow "$@" </dev/null 2>&1); then echo "FAIL: accepted: $*"; exit 1; fi
  echo "$err" | grep -qF -- "$text" || { echo "FAIL: '$*' said: $err"; exit 1; }
}
refused "copy the tool" --leader xarm --follower scara --joint-scale 1,1,1,1,1,1 --duration 1
refused "numbers separated by commas" --joint-scale 1,x --duration 1
refused "one per joint of 'xarm' (5)" --joint-scale 1,1 --duration 1
refused "--speed 2" --speed 2 --duration 1
echo "follow: session recorded and replayed, bad options refused"
