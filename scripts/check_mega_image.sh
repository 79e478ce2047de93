#!/bin/sh
# Checks the Mega controller image (firmware/mega, src/portable_controller) for what the
# firmware rules forbid: no heap and no C++ runtime support anywhere, and no floating-point
# routine called from an interrupt handler (the planner's float maths runs in the main loop
# only). Reads the ELF with avr-nm and avr-objdump.
# Usage: scripts/check_mega_image.sh build/firmware/mega_controller.elf
set -eu
elf=$1
nm=${AVR_NM:-avr-nm}
objdump=${AVR_OBJDUMP:-avr-objdump}

bad=$($nm "$elf" | grep -E ' (malloc|free|_Znw|_Znaj|_Zdl|_Zda|__cxa_[a-z_]+|__gxx_personality_v0)$' || true)
if [ -n "$bad" ]; then
  echo "check_mega_image: $elf pulls in heap or C++ runtime support:" >&2
  echo "$bad" >&2
  exit 1
fi

# Every interrupt handler's body (from its label to the next label) must call no float
# routine (__addsf3, __mulsf3, __fixunssfsi, sqrt, ...).
found=$($objdump -d "$elf" | awk '
  /^[0-9a-f]+ <.*>:$/ { in_isr = ($2 ~ /^<__vector_[0-9]+>:$/); name = $2; next }
  in_isr && /call|jmp/ && /<(__[a-z]*sf[0-9a-z]*|__fp_[a-z]+|sqrtf?|__float[a-z]+|__fix[a-z]+)>/ { print name ": " $0 }
')
if [ -n "$found" ]; then
  echo "check_mega_image: an interrupt handler calls floating-point routines:" >&2
  echo "$found" >&2
  exit 1
fi
isrs=$($objdump -d "$elf" | grep -c '^[0-9a-f]* <__vector_[0-9]*>:$' || true)
floats=$($nm "$elf" | grep -c -E ' (__addsf3|__mulsf3|__divsf3|sqrt)$' || true)
echo "check_mega_image: OK: no heap or C++ runtime; $isrs interrupt handlers, none calls float routines (float routines in the image: $floats, main loop only)"
