#!/usr/bin/env bash
# Runs every benchmark binary of a Release build; each prints BENCH lines.
set -euo pipefail
build=${1:-build/bench-release}
shopt -s nullglob
status=0
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" || status=1
done
exit $status
