#!/usr/bin/env bash
# The README starts with the two commands a new user runs on a fresh machine, and CI runs
# the test one: the first ```sh block of README.md must hold exactly `./setup demo` and
# `./setup test` (comments aside), .ci/run must run `./setup test`, and ./setup must be
# an executable script whose targets exist in the Makefile (and, with no target, a usage
# error that lists them).
set -euo pipefail
cd "$(dirname "$0")/../.."
block=$(awk '/^```sh$/ {on = 1; next} on && /^```$/ {exit} on' README.md | sed 's/[[:space:]]*#.*$//' | sed '/^$/d')
want=$'./setup demo\n./setup test'
bad=0
[ "$block" = "$want" ] || { echo "README's first sh block is:"; echo "$block"; echo "expected:"; echo "$want"; bad=1; }
grep -qx '\./setup test' .ci/run || { echo ".ci/run does not run './setup test'"; bad=1; }
[ -x setup ] || { echo "./setup is missing or not executable"; bad=1; }
head -1 setup | grep -q bash || { echo "./setup must be a bash script (a minimal Debian has bash, not make)"; bad=1; }
for target in demo test; do
    grep -q "^$target:" Makefile || { echo "the Makefile has no '$target' target"; bad=1; }
done
# ./setup with no target is a usage error (exit 2) that lists the targets, and installs nothing
rc=0
usage=$(./setup 2>&1) || rc=$?
[ $rc -eq 2 ] || { echo "./setup with no target exited $rc, expected 2"; bad=1; }
grep -q '\./setup demo' <<< "$usage" || { echo "./setup with no target does not list its targets"; bad=1; }
[ $bad -eq 0 ] || exit 1
echo "README commands: ./setup demo, ./setup test; .ci/run runs ./setup test"
