#!/usr/bin/env bash
# Runs every benchmark binary of a Release build; each prints BENCH lines.
set -euo pipefail
build=${1:-build/bench-release}
shopt -s nullglob
status=0
failed=()
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  if ! "$b"; then
    status=1
    failed+=("$(basename "$b")")
  fi
done
# Say which ones, so that a failed `make bench` is not a bare exit status at the end of a long log.
if [ $status -ne 0 ]; then
  echo "bench: failed: ${failed[*]} (their own messages are above)" >&2
fi
exit $status
