#!/usr/bin/env bash
# Runs every libFuzzer target for SECONDS each, starting from its seed corpus in fuzz/corpus/.
set -euo pipefail
build=${1:-build/fuzz}
seconds=${2:-60}
# A fixed seed (make test passes 1) makes a short run repeat the same inputs, so a finding in
# CI can be reproduced; `make fuzz` leaves it out and explores afresh every run.
seed=${3:-}
seed_flag=()
[ -n "$seed" ] && seed_flag=(-seed="$seed")
shopt -s nullglob
for f in "$build"/fuzz/fuzz_*; do
  [ -x "$f" ] || continue
  name=$(basename "$f")
  corpus="$build/corpus/$name"
  mkdir -p "$corpus"
  seeds=fuzz/corpus/$name
  echo "== $name for ${seconds}s"
  if [ -d "$seeds" ]; then
    "$f" "${seed_flag[@]}" -max_total_time="$seconds" -print_final_stats=1 "$corpus" "$seeds" 2>&1 | tail -n 3
  else
    "$f" "${seed_flag[@]}" -max_total_time="$seconds" -print_final_stats=1 "$corpus" 2>&1 | tail -n 3
  fi
done
