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
for f in "$build"/fuzz/fuzz_*; do
  [ -x "$f" ] || continue
  name=$(basename "$f")
  corpus="$build/corpus/$name"
  # A fixed number of runs starts from nothing but the seeds: what earlier runs found would
  # change the inputs tried.
  [ -n "$runs" ] && corpus="$build/test-corpus/$name" && rm -rf "$corpus"
  log="$build/$name.log"
  mkdir -p "$corpus"
  rm -f "$artifacts/$name-"*
  dirs=("$corpus")
  [ -d "fuzz/corpus/$name" ] && dirs+=("fuzz/corpus/$name")
  if [ -n "$runs" ]; then echo "== $name for $runs inputs (seed ${seed:-1})"; else echo "== $name for ${seconds}s"; fi
  # The whole log stays in $log; a finding prints what the fuzzer said about it and the input
  # that caused it (written to $artifacts), so that CI's output is enough to reproduce it.
  if "$f" "${limit_flags[@]}" -print_final_stats=1 \
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
