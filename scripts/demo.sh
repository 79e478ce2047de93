#!/usr/bin/env bash
# make demo: start the simulated SCARA arm in the background, drive all seven joints through
# a few moves over the joint bus, wait for each move, and print the positions as they go.
set -euo pipefail
armctl=${1:-build/armctl}
dir=$(mktemp -d)
sock="$dir/scara.sock"

"$armctl" sim scara --listen "$sock" > "$dir/sim.log" 2>&1 &
sim_pid=$!
trap 'kill "$sim_pid" 2>/dev/null; wait "$sim_pid" 2>/dev/null; rm -rf "$dir"' EXIT

for _ in $(seq 50); do [ -S "$sock" ] && break; sleep 0.1; done
[ -S "$sock" ] || { echo "demo: the simulated arm did not start:"; cat "$dir/sim.log"; exit 1; }

bus() { "$armctl" bus --device "unix:$sock" "$@"; }

echo "== every joint answers"
bus ping all
echo "== speed 60 %, zone 5 clicks"
bus speed all 60 > /dev/null
bus zone all 5 > /dev/null
for target in 3000 -1500 0; do
  echo "== drive-to all $target"
  bus drive-to all "$target" > /dev/null
  bus position all
  bus wait all --timeout 10
  bus position all
done
echo "== relative move of joint 2 by +800, joint 3 by -800"
bus drive-dist 2 800 > /dev/null
bus drive-dist 3 -800 > /dev/null
bus wait all --timeout 10 > /dev/null
bus position all
