#!/usr/bin/env bash
# Writes the EEPROM image (Intel HEX) that makes a joint controller board joint N.
#   tools/joint_eeprom.sh [--polarity original|reversed] [--dialect standard|legacy] \
#                         JOINT [BAUD] OUTPUT.eep
# JOINT 1..7; BAUD 9600 (default) or 115200; --polarity: original (default, the wiring of
# the original firmware: D11 counts the encoder up) or reversed; --dialect: standard
# (default) or legacy (legacy-master mode, for a bus still run by the original Mega master).
# Layout: firmware/board/joint_config.hpp (magic 0x4A, joint, settings = baud bit 0 |
# reversed bit 1 | legacy bit 2, check = 0xFF ^ magic ^ joint ^ settings).
# Program it with: avrdude -p atmega328p -c arduino -P PORT -b 115200 -U eeprom:w:OUTPUT.eep:i
set -euo pipefail

usage() {
  echo "usage: $0 [--polarity original|reversed] [--dialect standard|legacy] JOINT(1..7) [BAUD(9600|115200)] OUTPUT.eep" >&2
  exit 2
}
polarity=original
dialect=standard
while [ $# -gt 0 ]; do
  case "$1" in
    --polarity) [ $# -ge 2 ] || usage; polarity=$2; shift 2 ;;
    --dialect) [ $# -ge 2 ] || usage; dialect=$2; shift 2 ;;
    --*) echo "$0: unknown option '$1' (allowed: --polarity, --dialect)" >&2; exit 2 ;;
    *) break ;;
  esac
done
[ $# -eq 2 ] || [ $# -eq 3 ] || usage
joint=$1
if [ $# -eq 3 ]; then baud=$2; out=$3; else baud=9600; out=$2; fi

case "$joint" in
  [1-7]) ;;
  *) echo "$0: joint number '$joint' is not allowed: use 1..7" >&2; exit 2 ;;
esac
case "$baud" in
  9600) code=0 ;;
  115200) code=1 ;;
  *) echo "$0: baud '$baud' is not allowed: use 9600 or 115200" >&2; exit 2 ;;
esac

case "$polarity" in
  original) ;;
  reversed) code=$(( code | 2 )) ;;
  *) echo "$0: motor polarity '$polarity' is not allowed: use original or reversed" >&2; exit 2 ;;
esac
case "$dialect" in
  standard) ;;
  legacy) code=$(( code | 4 )) ;;
  *) echo "$0: dialect '$dialect' is not allowed: use standard or legacy" >&2; exit 2 ;;
esac

magic=$((0x4A))
check=$(( 0xFF ^ magic ^ joint ^ code ))
bytes=("$magic" "$joint" "$code" "$check")

# One Intel HEX data record at address 0, then the end-of-file record.
sum=$(( 4 + 0 + 0 + 0 ))
line=":04000000"
for b in "${bytes[@]}"; do
  line+=$(printf '%02X' "$b")
  sum=$(( sum + b ))
done
line+=$(printf '%02X' $(( (0x100 - (sum & 0xFF)) & 0xFF )))
mkdir -p "$(dirname "$out")"
printf '%s\n:00000001FF\n' "$line" > "$out"
echo "$out: joint $joint at $baud baud, motor polarity $polarity, $dialect master"
