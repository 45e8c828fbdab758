#!/usr/bin/env bash
# Prints the ctest -E expression that leaves out of the sanitizer run (.ci/run) every test case
# whose time in a Release run exceeded SECONDS: LOG is that run's LastTest.log (ctest writes it
# to BUILD/Testing/Temporary/; each case's block opens with "I/N Test: NAME" and holds
# "Test time = T sec"). Not CTestCostData.txt: ctest reads that file back split at spaces, so
# after a second run it holds only the first word of every name. The cases left out are the
# whole diagnoses, fits and transcripts that take 5-50x longer under AddressSanitizer; the code
# they run is run by the cheaper cases too, and the Release run ran them all. Prints on standard
# error how many cases are left out and their Release time. Fails when LOG is missing or times
# no test.
#
#   sanitizer_excludes.sh LOG SECONDS
set -euo pipefail
log=${1:?usage: sanitizer_excludes.sh LOG SECONDS}
seconds=${2:?usage: sanitizer_excludes.sh LOG SECONDS}
[ -s "$log" ] || { echo "$log: no test log (run the Release suite first: ctest writes it)" >&2; exit 1; }
awk -v limit="$seconds" -v file="$log" '
  /^[0-9]+\/[0-9]+ Test: / { name = $0; sub(/^[0-9]+\/[0-9]+ Test: /, "", name); next }
  /^Test time = / && name != "" {
    tests++
    cost = $4
    if (cost + 0 > limit + 0) {
      total += cost
      left_out++
      gsub(/[][\\.^$*+?()|{}]/, "\\\\&", name)
      expression = expression (expression == "" ? "" : "|") "^" name "$"
    }
    name = ""
  }
  END {
    if (tests == 0) { print file ": times no test" > "/dev/stderr"; exit 1 }
    printf "sanitizer run: %d of %d test cases left out (over %s s in the Release run, %.0f s there in all)\n", left_out, tests, limit, total > "/dev/stderr"
    # ctest -E needs an expression; one that matches no name leaves nothing out.
    print (expression == "" ? "^$" : expression)
  }' "$log"
