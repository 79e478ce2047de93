#!/bin/sh
# Proves that the portable joint-controller code builds unchanged for the ATmega328P:
# compiles every src/portable/*.cpp with avr-g++ (C++14, warnings are errors), links them
# with a small driver that calls every entry point, and checks the image pulls in no heap,
# no C++ runtime support and no floating-point routines. A missing avr-g++ is a failure.
# Usage: scripts/check_portable_avr.sh [repo root]
set -eu

root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cxx=${AVR_CXX:-avr-g++}
nm=${AVR_NM:-avr-nm}
size=${AVR_SIZE:-avr-size}

if ! command -v "$cxx" >/dev/null 2>&1; then
  echo "check_portable_avr: $cxx not found; install gcc-avr and avr-libc" >&2
  exit 1
fi

flags="-std=c++14 -mmcu=atmega328p -Os -Wall -Wextra -Werror -fno-exceptions -fno-rtti -I $root/src"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

objects=""
count=0
for src in "$root"/src/portable/*.cpp; do
  [ -e "$src" ] || { echo "check_portable_avr: no .cpp in $root/src/portable" >&2; exit 1; }
  obj="$work/$(basename "$src" .cpp).o"
  echo "avr-g++ $src"
  $cxx $flags -c "$src" -o "$obj"
  objects="$objects $obj"
  count=$((count + 1))
done

# A driver that uses every entry point, so the link keeps all of the code.
cat > "$work/driver.cpp" <<'CPP'
#include "portable/joint_controller.hpp"
using armctl::joint_bus::JointController;
static JointController joint;
volatile uint8_t sink;
int main() {
  armctl::joint_bus::JointOptions options;
  options.legacy_master = sink & 1;
  joint.begin(3, armctl::joint_bus::default_tuning(), 9600, options);
  joint.init_encoder(false, false);
  uint32_t now = 0;
  for (;;) {
    joint.on_select(true, now);
    joint.on_rx_byte(sink, now);
    joint.poll(now);
    uint8_t b;
    if (joint.next_tx_byte(&b)) sink = b;
    sink = joint.tx_enabled();
    joint.on_encoder_edge(sink & 1, sink & 2);
    armctl::joint_bus::DriveOutput out = joint.control_tick();
    joint.control_sample();
    out = joint.control_compute();
    sink = static_cast<uint8_t>(out.duty);
    sink = static_cast<uint8_t>(joint.position() + joint.target() + joint.loop_enabled());
    joint.set_board_diagnostics(armctl::joint_bus::BoardDiagnostics{{sink, sink, sink, sink}});
    sink = static_cast<uint8_t>(joint.faults() + joint.diagnostic(sink & 7));
    now += 1000;
  }
}
CPP
$cxx $flags -c "$work/driver.cpp" -o "$work/driver.o"
$cxx -mmcu=atmega328p -Os -Wl,--gc-sections $objects "$work/driver.o" -o "$work/joint.elf"

bad=$($nm "$work/joint.elf" | grep -E ' (malloc|free|_Znw|_Znaj|_Zdl|_Zda|__cxa_[a-z_]+|__gxx_personality_v0|__[a-z]+sf[0-9]|__fix[a-z]*sf[a-z]*|__float[a-z]+sf)$' || true)
if [ -n "$bad" ]; then
  echo "check_portable_avr: the AVR image pulls in heap, C++ runtime or float routines:" >&2
  echo "$bad" >&2
  exit 1
fi
$size "$work/joint.elf"
echo "check_portable_avr: OK, $count files compiled and linked for the ATmega328P"
