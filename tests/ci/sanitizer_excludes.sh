#!/usr/bin/env bash
# Prints the ctest -E expression that leaves out the test cases named in SKIPS (one exact ctest
# name a line, '#' comments; tests/ci/sanitizer_skips.txt) from the tests of BUILD_DIR. Fails,
# naming the line, when a name matches no test of BUILD_DIR, so that a renamed case cannot
# silently stop being left out (or a typo go unnoticed). Each name is matched whole: the
# regular-expression characters of a name are escaped and the expression anchored.
set -euo pipefail
build=${1:?usage: sanitizer_excludes.sh BUILD_DIR SKIPS}
skips=${2:?usage: sanitizer_excludes.sh BUILD_DIR SKIPS}
names=$(ctest --test-dir "$build" -N | sed -n 's/^ *Test *#[0-9]*: //p')
expression=
line_number=0
while IFS= read -r line || [ -n "$line" ]; do
  line_number=$((line_number + 1))
  case $line in '' | '#'*) continue ;; esac
  if ! grep -qxF -- "$line" <<<"$names"; then
    echo "$skips:$line_number: no test of $build is named '$line': correct the name or remove the line" >&2
    exit 1
  fi
  escaped=$(sed 's/[][\.^$*+?()|{}]/\\&/g' <<<"$line")
  expression+="${expression:+|}^${escaped}\$"
done <"$skips"
[ -n "$expression" ] || { echo "$skips: no test names" >&2; exit 1; }
printf '%s\n' "$expression"
