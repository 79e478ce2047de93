#!/usr/bin/env bash
# armctl completion bash and armctl manual (src/apps/armctl/cli_reference.hpp): the completion
# script completes command words, options and option values the way a user types them, and
# the manual page renders with man and names every command and its options.
set -uo pipefail
armctl=$1
build=$(dirname "$armctl")
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

script=$("$armctl" completion bash) || { echo "FAIL: armctl completion bash exited $?"; exit 1; }
eval "$script"
# complete WORDS...: what _armctl offers for the last word of `WORDS`.
complete_words() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _armctl
  echo "${COMPREPLY[*]}"
}
expect() {  # expect "what it offers" "a word it must hold" [more]
  local offered=$1
  shift
  for w in "$@"; do [[ " $offered " == *" $w "* ]] || fail "offered '$offered', missing '$w'"; done
}
expect "$(complete_words armctl ar)" arm
expect "$(complete_words armctl arm mo)" move-joints move-to
expect "$(complete_words armctl arm move-to --sp)" --speed
expect "$(complete_words armctl --arm scara arm move-to --li)" --linear
expect "$(complete_words armctl xarm group r)" run
expect "$(complete_words armctl program '')" check run compile
[[ "$(complete_words armctl arm mo)" != *serve* ]] || fail "commands of another level offered"
# After an option that takes a value: files (an arm file, a program).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
touch "$tmp/pick.prog"
expect "$(complete_words armctl program run --arm "$tmp/pi")" "$tmp/pick.prog"
expect "$(complete_words armctl program run "$tmp/pi")" "$tmp/pick.prog"

# What `make install` installs is what the command prints.
"$armctl" completion bash | cmp -s - "$build/share/bash-completion/completions/armctl" ||
  fail "build/share/bash-completion/completions/armctl is not what armctl completion bash prints"

page=$("$armctl" manual) || { echo "FAIL: armctl manual exited $?"; exit 1; }
rendered=$(MANWIDTH=100 man -l - <<<"$page" 2> "$tmp/man.err") || fail "man -l could not render the page"
grep -v "cannot adjust line" "$tmp/man.err" | grep -q . && fail "man said: $(cat "$tmp/man.err")"
for heading in NAME SYNOPSIS DESCRIPTION COMMANDS "EXIT STATUS" "SEE ALSO"; do
  grep -q "^$heading" <<<"$rendered" || fail "no $heading section"
done
for command in "armctl arm move-to" "armctl program run" "armctl xarm group download" "armctl serve" \
               "armctl bus drive-to" "armctl sim scara" "armctl teach" "armctl replay"; do
  grep -q "^   $command\$" <<<"$rendered" || fail "the manual has no '$command'"
done
grep -q -- "--linear" <<<"$rendered" || fail "the manual has no --linear"
grep -q "^       130" <<<"$rendered" || grep -q "128 + N" <<<"$rendered" || fail "no exit statuses"
"$armctl" manual | cmp -s - "$build/share/man/man1/armctl.1" ||
  fail "build/share/man/man1/armctl.1 is not what armctl manual prints"

[ "$failures" -eq 0 ] && echo "completion and manual: ok"
exit $((failures > 0))
