#!/usr/bin/env bash
# Runs every libFuzzer target, starting from its seed corpus in fuzz/corpus/.
#   scripts/fuzz.sh BUILD SECONDS          explore afresh for SECONDS per target (make fuzz),
#                                          growing BUILD/corpus/<target> from run to run
#   scripts/fuzz.sh BUILD SECONDS SEED RUNS   RUNS inputs per target from the seed corpus alone,
#                                          with a fixed SEED (make test): the same inputs on every
#                                          machine, so a finding in CI is one a local run finds too
#                                          (a time budget would run more inputs on a faster machine)
set -euo pipefail
build=${1:-build/fuzz}
seconds=${2:-60}
seed=${3:-}
runs=${4:-}
limit_flags=(-max_total_time="$seconds")
[ -n "$seed" ] && limit_flags+=(-seed="$seed")
# A generous time cap too, so that a target far slower than expected cannot hold CI.
[ -n "$runs" ] && limit_flags=(-seed="${seed:-1}" -runs="$runs" -max_total_time=600)
shopt -s nullglob
artifacts="$build/artifacts"
mkdir -p "$artifacts"
# One target: its log in $build/<target>.log; prints its last lines, or on a finding what the
# fuzzer said about it and the input that caused it (written to $artifacts), so that CI's
# output is enough to reproduce it.
run_target() {
  local f=$1 name corpus log status
  name=$(basename "$f")
  corpus="$build/corpus/$name"
  # A fixed number of runs starts from nothing but the seeds: what earlier runs found would
  # change the inputs tried.
  [ -n "$runs" ] && corpus="$build/test-corpus/$name" && rm -rf "$corpus"
  log="$build/$name.log"
  mkdir -p "$corpus"
  rm -f "$artifacts/$name-"*
  local dirs=("$corpus")
  [ -d "fuzz/corpus/$name" ] && dirs+=("fuzz/corpus/$name")
  if "$f" "${limit_flags[@]}" -print_final_stats=1 \
       -artifact_prefix="$artifacts/$name-" "${dirs[@]}" > "$log" 2>&1; then
    if [ -n "$runs" ]; then echo "== $name: $runs inputs (seed ${seed:-1})"; else echo "== $name: ${seconds}s"; fi
    tail -n 3 "$log"
  else
    status=$?
    grep -v '^#[0-9]' "$log" | grep -v '^"' | tail -n 40
    for a in "$artifacts/$name-"*; do
      echo "-- input $a (reproduce: $f $a):"
      od -c "$a" | head -n 20
    done
    echo "== $name FAILED (exit $status)"
    return "$status"
  fi
}

# Targets run JOBS at a time (each fuzzer is one process on one core); their lines are printed
# at the end, target by target, so that two never interleave. Any failure fails the run.
jobs=${JOBS:-2}
targets=()
for f in "$build"/fuzz/fuzz_*; do [ -x "$f" ] && targets+=("$f"); done
failed=0
running=0
for f in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
  run_target "$f" > "$build/$(basename "$f").out" 2>&1 &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
for f in "${targets[@]}"; do cat "$build/$(basename "$f").out"; done
exit "$failed"
