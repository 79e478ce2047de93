#!/usr/bin/env bash
# README "Try it without hardware" run as printed, in one shell as a user pastes it: this
# build's armctl for build/armctl, and a temporary folder for /tmp/scara.sock, /tmp/xarm and
# ~/.armctl/xarm (nothing else is changed). Every command must succeed, except the one the
# README shows failing (a joint that never answers: exit 1, joint 6 reported as FAILED).
set -uo pipefail
armctl=$1
readme=$2
tmp=$(mktemp -d /tmp/armctl-try-it-XXXXXX)
cleanup() {
  for p in $(jobs -p); do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$tmp"
}
trap cleanup EXIT

block=$(awk '/^## Try it without hardware/{s=1} s && /^```sh/{f=1; next} f && /^```/{exit} f' "$readme")
[ -n "$block" ] || { echo "FAIL: no sh block under '## Try it without hardware' in $readme"; exit 1; }
failures=0
commands=0
while IFS= read -r line; do
  [[ -z "${line// }" || "$line" =~ ^[[:space:]]*# ]] && continue
  run=${line//build\/armctl/$armctl}
  run=${run//\/tmp\/scara.sock/$tmp\/scara.sock}
  run=${run//\/tmp\/xarm/$tmp\/xarm}
  run=${run//\~\/.armctl\/xarm/$tmp\/state}
  commands=$((commands + 1))
  if [[ "$line" == *"&"*"#"* || "$line" =~ \&[[:space:]]*$ ]]; then
    eval "${run%%#*}" > "$tmp/background-$commands.log" 2>&1  # started in the background, as printed
    continue
  fi
  out=$(eval "$run" 2>&1)
  status=$?
  if [[ "$line" == *"dead=6"* ]]; then
    [ $status -eq 1 ] && grep -q "joint 6: FAILED no answer (990)" <<<"$out" ||
      { echo "FAIL: $line: expected exit 1 naming joint 6, got $status: $out"; failures=$((failures + 1)); }
  elif [ $status -ne 0 ]; then
    echo "FAIL: $line: exit $status: $out"
    failures=$((failures + 1))
  fi
done <<<"$block"
[ "$commands" -ge 10 ] || { echo "FAIL: only $commands commands found in the block"; exit 1; }
[ "$failures" -eq 0 ] && echo "README 'Try it without hardware': $commands commands as printed: ok"
exit $((failures > 0))
