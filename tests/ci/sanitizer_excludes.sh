#!/usr/bin/env bash
# Prints the ctest -E expression that leaves out of the sanitizer run (.ci/run) every test case
# whose cost in a Release run exceeded SECONDS: COSTS is that run's CTestCostData.txt (ctest
# writes it to BUILD/Testing/Temporary/; a line per test, "NAME RUNS AVERAGE_SECONDS", then a
# line "---" and the names of failed tests). The cases left out are the whole diagnoses, fits and
# transcripts that take 5-50x longer under AddressSanitizer; the code they run is run by the
# cheaper cases too, and the Release run ran them all. Prints on standard error how many cases
# are left out and their Release time. Fails when COSTS is missing or lists no test.
#
#   sanitizer_excludes.sh COSTS SECONDS
set -euo pipefail
costs=${1:?usage: sanitizer_excludes.sh COSTS SECONDS}
seconds=${2:?usage: sanitizer_excludes.sh COSTS SECONDS}
[ -s "$costs" ] || { echo "$costs: no test costs (run the Release suite first: it writes them)" >&2; exit 1; }
# NAME may hold spaces: the last two fields are the count of runs and the average.
awk -v limit="$seconds" -v file="$costs" '
  $0 == "---" { exit }
  NF >= 3 {
    tests++
    cost = $NF
    if (cost + 0 <= limit + 0) next
    name = $0
    sub(/ +[^ ]+ +[^ ]+$/, "", name)
    gsub(/[][\\.^$*+?()|{}]/, "\\\\&", name)
    expression = expression (expression == "" ? "" : "|") "^" name "$"
    left_out++
    total += cost
  }
  END {
    if (tests == 0) { print file ": lists no test" > "/dev/stderr"; exit 1 }
    printf "sanitizer run: %d of %d test cases left out (over %s s in the Release run, %.0f s there in all)\n", left_out, tests, limit, total > "/dev/stderr"
    # ctest -E needs an expression; one that matches no name leaves nothing out.
    print (expression == "" ? "^$" : expression)
  }' "$costs"
