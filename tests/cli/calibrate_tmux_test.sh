#!/bin/bash
# armctl calibrate in a real terminal (tmux), on the embedded mis-assembled SCARA with an arm
# file of the test's own: the direction step answered as typed (a wrong answer asked again, a
# joint redone), the changes shown, then refused at the confirm (the file unchanged, no .prev),
# then confirmed (written, the old file kept as .prev); the zero step left with Ctrl-C (exit
# 130, nothing written); bad arguments refused naming what is allowed. Waits poll for what the
# screen shows (no fixed settling). Then the xArm's find step on its mis-assembled emulator.
set -euo pipefail
armctl=$1
run=0
sock="armctl-calibrate-test-$$-$run"
dir=$(mktemp -d)
tm() { tmux -L "$sock" "$@"; }
trap 'tm kill-server 2>/dev/null || true; rm -rf "$dir"' EXIT
src=$(cd "$(dirname "$0")/../.." && pwd)
cp "$src/config/scara.arm.json" "$src/config/scara.urdf" "$dir/"
file="$dir/scara.arm.json"
orig=$(sha256sum "$file" | cut -d' ' -f1)

screen() { tm capture-pane -p -t cal -S -200 2>/dev/null || true; }
wait_for() {  # wait_for TEXT [COUNT]: up to 60 s for TEXT on the screen (COUNT times)
  local n=${2:-1}
  for _ in $(seq 600); do
    if [ "$(screen | grep -cF -- "$1")" -ge "$n" ]; then return 0; fi
    sleep 0.1
  done
  echo "FAIL: '$1' never showed ($n times); the screen:"; screen; exit 1
}
fail() { echo "FAIL: $1"; screen; exit 1; }
start() {  # start ARGS...: armctl calibrate in a fresh tmux window
  tm kill-server 2>/dev/null || true
  run=$((run + 1)); sock="armctl-calibrate-test-$$-$run"  # a server of its own each time
  tm new-session -d -s cal -x 200 -y 60 \
    "ASAN_OPTIONS=detect_leaks=0 ARMCTL_STATE_DIR=$dir/state $armctl calibrate --arm $file --device 'sim?miscal=7' $*; echo cal-exit=\$?; sleep 600"
}
# Answers the direction step: y for every joint but UAJ (n); a wrong word first, and SHOULDER redone.
answer_directions() {
  local k=0
  for joint in Z SHOULDER UAE UAJ SKE SKF; do
    k=$((k + 1))
    wait_for "Did $joint go the way"
    case $joint in
      Z) tm send-keys -t cal maybe Enter; wait_for "'maybe': allowed y, n, r (redo), s (skip), q (quit)"
         wait_for "Did Z go the way" 2; tm send-keys -t cal y Enter ;;
      SHOULDER) tm send-keys -t cal r Enter; wait_for "Did SHOULDER go the way" 2; tm send-keys -t cal y Enter ;;
      UAJ) tm send-keys -t cal n Enter ;;
      *) tm send-keys -t cal y Enter ;;
    esac
  done
  wait_for "== changes =="
  screen | grep -qF "UAJ: direction flipped" || fail "the flip of UAJ is not shown"
}

# 1. Shown, then refused: nothing written.
start direction
answer_directions
wait_for "Write these to $file"
tm send-keys -t cal n Enter
wait_for "cal-exit="
screen | grep -qF "Not written." || fail "no 'Not written.'"
screen | grep -qF "cal-exit=0" || fail "a refusal at the confirm should exit 0"
[ "$(sha256sum "$file" | cut -d' ' -f1)" = "$orig" ] || fail "the arm file changed though not confirmed"
[ ! -e "$file.prev" ] || fail "a .prev was written though not confirmed"

# 2. Confirmed: written, the old file kept.
start direction
answer_directions
wait_for "Write these to $file"
tm send-keys -t cal y Enter
wait_for "cal-exit="
screen | grep -qF "Written: $file" || fail "no 'Written:' line"
screen | grep -qF "cal-exit=0" || fail "armctl calibrate did not exit 0"
[ "$(sha256sum "$file.prev" | cut -d' ' -f1)" = "$orig" ] || fail ".prev is not the file as it was"
[ "$(sha256sum "$file" | cut -d' ' -f1)" != "$orig" ] || fail "the arm file did not change"
written=$(sha256sum "$file" | cut -d' ' -f1)

# 3. Ctrl-C in the zero step: exit 130, nothing written.
start zero --joint SHOULDER
wait_for "Move SHOULDER by hand to its mark"
tm send-keys -t cal C-c
wait_for "cal-exit="
screen | grep -qF "cal-exit=130" || fail "Ctrl-C should exit 130"
[ "$(sha256sum "$file" | cut -d' ' -f1)" = "$written" ] || fail "Ctrl-C changed the arm file"

# 4. Bad arguments: refused, naming what is allowed.
set +e
out=$(ASAN_OPTIONS=detect_leaks=0 "$armctl" calibrate --arm "$file" --device 'sim?miscal=7' wobble 2>&1); rc=$?
set -e
[ $rc -ne 0 ] && echo "$out" | grep -qF "step 'wobble': allowed all, find, which" || { echo "FAIL: bad step: $rc $out"; exit 1; }
set +e
out=$(ASAN_OPTIONS=detect_leaks=0 "$armctl" calibrate --arm "$file" --device 'sim?miscal=7' --joint elbow direction 2>&1); rc=$?
set -e
[ $rc -ne 0 ] && echo "$out" | grep -qF "joint 'elbow': allowed a number 1..7 or a name" || { echo "FAIL: bad joint: $rc $out"; exit 1; }
[ "$(sha256sum "$file" | cut -d' ' -f1)" = "$written" ] || fail "a refused argument changed the arm file"
# 4b. The touch step's typed points: a line that is not NAME X Y Z, a point beyond reach, each
# refused naming what is allowed; a good one touched; nothing to write.
out=$(printf 'P1 1 2\nP2 5000 0 50\nP3 280 60 50\nd\n' | ASAN_OPTIONS=detect_leaks=0 ARMCTL_STATE_DIR="$dir/state" \
        "$armctl" calibrate --arm "$file" --device 'sim?miscal=7' touch 2>&1) || { echo "FAIL: touch: $out"; exit 1; }
echo "$out" | grep -qF "'P1 1 2': allowed Enter (on the mark), NAME X Y Z in mm, d, s or q" || { echo "FAIL: $out"; exit 1; }
echo "$out" | grep -qF "point 'P2': x 5000 mm is beyond reach" || { echo "FAIL: $out"; exit 1; }
echo "$out" | grep -qF "P3 touched (1 points)" || { echo "FAIL: $out"; exit 1; }
echo "$out" | grep -qF "nothing to write" || { echo "FAIL: $out"; exit 1; }
[ "$(sha256sum "$file" | cut -d' ' -f1)" = "$written" ] || fail "the touch step changed the arm file"

# 5. The xArm's find step on its mis-assembled emulator: the place whose servo answers another
# ID gives no answer, and the wizard says that setting an ID reaches every servo.
cp "$src/config/xarm.arm.json" "$src/config/xarm.urdf" "$dir/"
out=$(printf '\n' | ASAN_OPTIONS=detect_leaks=0 ARMCTL_STATE_DIR="$dir/xstate" "$armctl" calibrate --arm "$dir/xarm.arm.json" \
        --device 'sim?miscal=7' find 2>&1) || { echo "FAIL: find: $out"; exit 1; }
echo "$out" | grep -q "(ID [2-6]): NO ANSWER" || { echo "FAIL: no silent ID: $out"; exit 1; }
echo "$out" | grep -qF "reaches EVERY servo on the bus" || { echo "FAIL: no word of BusServoInfoWrite: $out"; exit 1; }
echo "$out" | grep -qF "nothing to write" || { echo "FAIL: $out"; exit 1; }

# 6. The pictures (docs/calibration.md "Pictures"): written for an arm file without a device; with
# a device or a step refused (it opens none); a path that cannot be written named.
out=$(ASAN_OPTIONS=detect_leaks=0 "$armctl" calibrate --arm "$file" --pictures "$dir/joints.svg" 2>&1) || { echo "FAIL: pictures: $out"; exit 1; }
echo "$out" | grep -qF "7 joints of scara" || { echo "FAIL: $out"; exit 1; }
[ "$(grep -c 'grey: at its mark' "$dir/joints.svg")" = 7 ] || fail "not one panel per joint in $dir/joints.svg"
set +e
out=$(ASAN_OPTIONS=detect_leaks=0 "$armctl" calibrate --arm "$file" --device 'sim?miscal=7' --pictures "$dir/j2.svg" 2>&1); rc=$?
set -e
[ $rc -ne 0 ] && echo "$out" | grep -qF -- "--pictures opens no device" || { echo "FAIL: pictures with a device: $rc $out"; exit 1; }
set +e
out=$(ASAN_OPTIONS=detect_leaks=0 "$armctl" calibrate --arm "$file" --pictures "$dir/no/such/dir/j.svg" 2>&1); rc=$?
set -e
[ $rc -ne 0 ] && echo "$out" | grep -qF "$dir/no/such/dir" || { echo "FAIL: unwritable pictures: $rc $out"; exit 1; }
echo "calibrate under tmux: refused, confirmed, interrupted and bad arguments as expected"
