#!/usr/bin/env bash
# make demo: five parts, each announced by a "[n/5]" line with the time since the start.
#   1 the SCARA arm's seven joints over the joint bus (ping, moves, wait, read back)
#   2 one program, two arms, one SDK: the simulated SCARA arm (seven joints on a simulated
#     joint bus, driven by the arm controller: a Robot Commands device on a pty) and the
#     emulated xArm (six bus servos, Robot Commands on a pty) run the same short program with
#     `armctl xarm` (synchronized moves and an action group)
#   3 the Arm API in millimetres: each arm's tool to three points, the pose read back
#   4 host-planned paths: each arm's tool draws a square with blended corners
#   5 a robot program: the same pick-and-place on both arms
# Parts 4 and 5 write --trace files; at the end scripts/demo_picture.py draws them into
# OUT/demo.svg (OUT: the second argument, default the folder of the armctl binary).
set -euo pipefail
armctl=${1:-build/armctl}
out=${2:-$(dirname "$armctl")}
[ -x "$armctl" ] || { echo "demo: $armctl is not an executable (make demo builds it)"; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
dir=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
  rm -rf "$dir"
}
trap cleanup EXIT

part() {  # n title: the part's header line, with the time since the demo started
  printf '\n[%s/5] %s  (at %d:%02d)\n' "$1" "$2" $((SECONDS / 60)) $((SECONDS % 60))
}

# Part 1: the SCARA arm at the joint-bus level: a simulated arm that keeps its state, driven
# joint by joint with `armctl bus` (what the arm controller does underneath).
part 1 "The SCARA arm's seven joints over the joint bus: ping, drive, wait, read back"
"$armctl" sim scara --listen "$dir/bus.sock" > "$dir/bus.log" 2>&1 &
bus_pid=$!
pids+=($bus_pid)
for _ in $(seq 50); do [ -S "$dir/bus.sock" ] && break; sleep 0.1; done
[ -S "$dir/bus.sock" ] || { echo "demo: the simulated arm did not start:"; cat "$dir/bus.log"; exit 1; }
bus() { "$armctl" bus --device "unix:$dir/bus.sock" "$@"; }
echo "== joint bus: every joint answers"
bus ping all
bus speed all 60 > /dev/null
bus zone all 5 > /dev/null
for target in 3000 0; do
  echo "== joint bus: drive-to all $target clicks at 60 % speed, wait, read back"
  bus drive-to all "$target" > /dev/null
  bus wait all --timeout 10
  bus position all
done

# Part 2: one program, two arms, one SDK.
part 2 "One program, two arms, one SDK: synchronized moves and an action group on the SCARA arm and the xArm"
"$armctl" sim scara --robot-commands --link "$dir/scara" > /dev/null 2> "$dir/scara.log" &
pids+=($!)
"$armctl" sim xarm --link "$dir/xarm" > /dev/null 2> "$dir/xarm.log" &
pids+=($!)
for _ in $(seq 100); do [ -e "$dir/scara" ] && [ -e "$dir/xarm" ] && break; sleep 0.1; done
[ -e "$dir/scara" ] || { echo "demo: the SCARA arm did not start:"; cat "$dir/scara.log"; exit 1; }
[ -e "$dir/xarm" ] || { echo "demo: the xArm emulator did not start:"; cat "$dir/xarm.log"; exit 1; }

# The program: the same for both arms (servos 1..6; the SCARA's joint 7, the gripper, too).
cat > "$dir/wave.grp" <<'GROUP'
# wave: three joints, three actions of one second
servos 3
1000  1=550 2=450 3=550
1000  1=450 2=550 3=450
1000  1=500 2=500 3=500
GROUP

program() {  # name device servo-count
  local name=$1 device=$2 servos=$3
  local x=("$armctl" xarm --device "serial:$device" --servos "$servos")
  echo "== $name: battery"
  "${x[@]}" battery
  echo "== $name: synchronized move of six servos in 1.5 s"
  "${x[@]}" move 1=600 2=550 3=400 4=600 5=450 6=550 --time 1500 --wait
  echo "== $name: and back in 1.5 s"
  "${x[@]}" move 1=400 2=450 3=600 4=400 5=550 6=450 --time 1500 --wait
  echo "== $name: action group 1 (wave) downloaded, run once"
  "${x[@]}" group download "$dir/wave.grp" --group 1
  "${x[@]}" group run 1 --times 1 --wait
  echo "== $name: positions at the end"
  "${x[@]}" positions
}

program "SCARA (arm controller, 7 joints)" "$dir/scara" 7
program "xArm (emulated, 6 servos)" "$dir/xarm" 6
echo "== what the SCARA controller logged"
grep -v "^sim scara: joint [0-9] " "$dir/scara.log" || true

# Part 3: the Arm API, in SI units. Each arm's tool to three points given in millimetres
# (PTP through the analytic IK), then the pose read back and how far it is from the point.
part 3 "The Arm API in millimetres: each arm's tool to three points, the pose read back"
tool_to() {  # name arm device x y z [orientation...]
  local name=$1 arm=$2 device=$3 x=$4 y=$5 z=$6
  shift 6
  echo "== $name: tool to x=$x y=$y z=$z mm $*"
  "$armctl" arm --arm "$arm" --device "$device" move-to "x=$x" "y=$y" "z=$z" "$@" --time 2s --wait |
    grep -E '^(tool|position error)'
}
for p in "150 0 150" "100 120 100" "180 -60 60"; do
  tool_to "xArm (emulated, Robot Commands)" xarm "serial:$dir/xarm" $p
done
for p in "400 100 300" "300 -250 250" "500 200 350"; do
  tool_to "SCARA (joint bus)" scara "unix:$dir/bus.sock" $p roll=180deg pitch=0deg yaw=0deg
done
echo "== SCARA through the arm controller (Robot Commands: 0..1000 per joint, coarser)"
tool_to "SCARA (arm controller)" scara "serial:$dir/scara" 400 100 300 roll=180deg pitch=0deg yaw=0deg

# Part 4: motion planned on the host. Each arm's tool draws a square with blended corners
# (a PTP to the first corner, then four LIN moves with fly-by zones), checked whole before
# anything moves, streamed at the rate the link allows; the path error is measured from the
# positions read back while the arm moves.
# The greps drop the joint table printed at the end (stdout); the progress line is stderr.
part 4 "Motion planned on the host: each arm's tool draws a square with blended corners"
paths=$(cd "$(dirname "$0")/../examples/paths" && pwd)
echo "== xArm (emulated): a square with blended corners ($paths/xarm-square.path)"
"$armctl" arm --arm xarm --device "serial:$dir/xarm" path "$paths/xarm-square.path" \
  --trace "$out/xarm-square.csv" | grep -v '^servo'
echo "== SCARA (joint bus): a square with blended corners ($paths/scara-square.path)"
"$armctl" arm --arm scara --device "unix:$dir/bus.sock" path "$paths/scara-square.path" \
  --trace "$out/scara-square.csv" | grep -Ev '^(Z|SHOULDER|UAE|UAJ|SKE|SKF|SKG) '

# Part 5: a robot program (docs/programs.md). The same pick-and-place (a loop, subroutines
# with parameters, the gripper, PRINT) on both arms, each with its own points file: checked
# whole first (every move reachable and inside the joint limits, the run time estimated),
# then run; and compiled to an action group the xArm board replays without a host.
part 5 "A robot program: the same pick-and-place on both arms, checked whole, then run"
programs=$(cd "$(dirname "$0")/../examples/programs" && pwd)
echo "== xArm (emulated): check and run $programs/xarm-pick-place.prog"
"$armctl" program check "$programs/xarm-pick-place.prog" --arm xarm --device "serial:$dir/xarm" | tail -n 1
"$armctl" program run "$programs/xarm-pick-place.prog" --arm xarm --device "serial:$dir/xarm" \
  --trace "$out/xarm-pick-place.csv"
echo "== xArm (emulated): the same program as action group 5, replayed by the board alone"
"$armctl" program compile "$programs/xarm-pick-place.prog" --arm xarm --device "serial:$dir/xarm" --group 5 2>/dev/null
echo "== SCARA (joint bus): check and run $programs/scara-pick-place.prog"
"$armctl" program check "$programs/scara-pick-place.prog" --arm scara --device "unix:$dir/bus.sock" | tail -n 1
"$armctl" program run "$programs/scara-pick-place.prog" --arm scara --device "unix:$dir/bus.sock" \
  --trace "$out/scara-pick-place.csv"

printf "\nNext: drive either arm from a browser (docs/dashboard.md):\n"
echo "   $armctl serve --arm xarm     # then open http://127.0.0.1:8080/ (STOP button and Esc always stop it)"

# The picture: both arms' squares and pick-and-place, planned and measured, path errors.
# The squares without the PTP that brings the tool to the first corner (@: the LINs' lines).
python3 "$(dirname "$0")/demo_picture.py" "$out/demo.svg" \
  "xArm: the square=$out/xarm-square.csv@6-9" "xArm: the pick-and-place=$out/xarm-pick-place.csv" \
  "SCARA: the square=$out/scara-square.csv@4-7" "SCARA: the pick-and-place=$out/scara-pick-place.csv"
printf '\nDemo done in %d:%02d. What both arms did, planned and measured: %s\n' \
  $((SECONDS / 60)) $((SECONDS % 60)) "$out/demo.svg"
echo "   (the traces it is drawn from, CSV: $out/*-square.csv, $out/*-pick-place.csv)"
