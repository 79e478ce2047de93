#!/usr/bin/env bash
# Runs every libFuzzer target for SECONDS each, starting from its seed corpus in fuzz/corpus/.
set -euo pipefail
build=${1:-build/fuzz}
seconds=${2:-60}
shopt -s nullglob
for f in "$build"/fuzz/fuzz_*; do
  [ -x "$f" ] || continue
  name=$(basename "$f")
  corpus="$build/corpus/$name"
  mkdir -p "$corpus"
  seeds=fuzz/corpus/$name
  echo "== $name for ${seconds}s"
  if [ -d "$seeds" ]; then
    "$f" -max_total_time="$seconds" -print_final_stats=1 "$corpus" "$seeds" 2>&1 | tail -n 3
  else
    "$f" -max_total_time="$seconds" -print_final_stats=1 "$corpus" 2>&1 | tail -n 3
  fi
done
