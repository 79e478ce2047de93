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
artifacts="$build/artifacts"
mkdir -p "$artifacts"
for f in "$build"/fuzz/fuzz_*; do
  [ -x "$f" ] || continue
  name=$(basename "$f")
  corpus="$build/corpus/$name"
  log="$build/$name.log"
  mkdir -p "$corpus"
  rm -f "$artifacts/$name-"*
  dirs=("$corpus")
  [ -d "fuzz/corpus/$name" ] && dirs+=("fuzz/corpus/$name")
  echo "== $name for ${seconds}s"
  # The whole log stays in $log; a finding prints what the fuzzer said about it and the input
  # that caused it (written to $artifacts), so that CI's output is enough to reproduce it.
  if "$f" "${seed_flag[@]}" -max_total_time="$seconds" -print_final_stats=1 \
       -artifact_prefix="$artifacts/$name-" "${dirs[@]}" > "$log" 2>&1; then
    tail -n 3 "$log"
  else
    status=$?
    grep -v '^#[0-9]' "$log" | grep -v '^"' | tail -n 40
    for a in "$artifacts/$name-"*; do
      echo "-- input $a (reproduce: $f $a):"
      od -c "$a" | head -n 20
    done
    echo "== $name FAILED (exit $status)"
    exit "$status"
  fi
done
