#!/bin/sh
# Measures the joint controller's worst-case cycle counts on the ATmega328P: builds
# tests/portable/avr/measure_cycles.cpp with every src/portable/*.cpp with the firmware's
# optimisation flags (firmware/avr_flags.rsp: -Os -flto; override with AVR_OPT, e.g.
# AVR_OPT=-Os for a build without link-time optimisation), runs it in simavr at 16 MHz and prints one line per
# entry point, then the budget lines:
#   BENCH <name> <worst cycles> cycles limit <L> ratio <worst/L>   (lower is better)
# Budgets (firmware issue): control tick <= 1600 cycles (10 % of 1 ms at 16 MHz), encoder
# edge <= 100 cycles. Exit status 1 if a tool is missing or the run fails, 2 if over budget.
# Usage: scripts/measure_portable_avr_cycles.sh [repo root]
set -eu

root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cxx=${AVR_CXX:-avr-g++}
sim=${SIMAVR:-simavr}
for tool in "$cxx" "$sim"; do
  command -v "$tool" >/dev/null 2>&1 || { echo "measure_portable_avr_cycles: $tool not found" >&2; exit 1; }
done

opt=${AVR_OPT:--Os -flto}
flags="-std=c++14 -mmcu=atmega328p $opt -Wall -Wextra -Werror -fno-exceptions -fno-rtti -I $root/src"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

objects=""
for src in "$root"/src/portable/*.cpp "$root"/tests/portable/avr/measure_cycles.cpp; do
  obj="$work/$(basename "$src" .cpp).o"
  $cxx $flags -c "$src" -o "$obj"
  objects="$objects $obj"
done
$cxx -mmcu=atmega328p $opt -Wl,--gc-sections $objects -o "$work/measure.elf"

# simavr prints the UART output (with colour codes); it exits when the program sleeps with
# interrupts off.
timeout 300 "$sim" -m atmega328p -f 16000000 "$work/measure.elf" > "$work/out.txt" 2>&1 || true
# It shows each newline as '.' followed by a line break.
sed 's/\x1b\[[0-9;]*m//g; s/\.$//' "$work/out.txt" | tr -d '\r' | grep -E '^[a-z_]+ [0-9]+ [0-9]+ [0-9]+$|^done$' > "$work/lines.txt" || true
if ! grep -q '^done$' "$work/lines.txt"; then
  echo "measure_portable_avr_cycles: the simulated run did not finish; simavr said:" >&2
  cat "$work/out.txt" >&2
  exit 1
fi

echo "entry point        worst  mean  calls   (cycles at 16 MHz)"
grep -v '^done$' "$work/lines.txt" | while read -r name worst mean calls; do
  printf '%-17s %6s %5s %6s   worst %s us\n' "$name" "$worst" "$mean" "$calls" \
    "$(awk -v c="$worst" 'BEGIN { printf "%.1f", c / 16 }')"
done

status=0
bench() {  # name, entry point, limit
  worst=$(awk -v n="$2" '$1 == n { print $2 }' "$work/lines.txt")
  [ -n "$worst" ] || { echo "measure_portable_avr_cycles: no figure for $2" >&2; exit 1; }
  ratio=$(awk -v w="$worst" -v l="$3" 'BEGIN { printf "%.3f", w / l }')
  echo "BENCH $1 $worst cycles limit $3 ratio $ratio"
  [ "$worst" -le "$3" ] || status=2
}
bench portable_control_tick_cycles control_tick 1600
bench portable_control_compute_cycles control_compute 1600
bench portable_encoder_edge_cycles on_encoder_edge 100
exit $status
