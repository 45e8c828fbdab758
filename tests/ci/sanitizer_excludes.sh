#!/usr/bin/env bash
# Prints the ctest -E expression that leaves out of the sanitizer run (.ci/run) every test case
# whose time in a Release run exceeded SECONDS: LOG is that run's LastTest.log (ctest writes it
# to BUILD/Testing/Temporary/; each case's block opens with "I/N Test: NAME" and holds
# "Test time = T sec"). Not CTestCostData.txt: ctest reads that file back split at spaces, so
# after a second run it holds only the first word of every name. The cases left out are the
# whole diagnoses, fits and transcripts that take 5-50x longer under AddressSanitizer; the code
# they run is run by the cheaper cases too, and the Release run ran them all.
# SANITIZER_BUILD is the build the expression is for: a test there that sets up a fixture
# (FIXTURES_SETUP, as fmusim_build) is never left out, however long it took, since ctest -E drops
# a fixture's setup too and every case that needs it would fail.
# Prints on standard error how many cases are left out and their Release time. Fails when LOG is
# missing or times no test, or when ctest cannot list SANITIZER_BUILD's tests.
#
#   sanitizer_excludes.sh LOG SECONDS SANITIZER_BUILD
set -euo pipefail
usage="usage: sanitizer_excludes.sh LOG SECONDS SANITIZER_BUILD"
log=${1:?$usage}
seconds=${2:?$usage}
build=${3:?$usage}
[ -s "$log" ] || { echo "$log: no test log (run the Release suite first: ctest writes it)" >&2; exit 1; }
listing=$(ctest --test-dir "$build" --show-only=json-v1) && grep -q '"name" : "' <<<"$listing" \
  || { echo "$build: ctest lists no tests there (configure it first)" >&2; exit 1; }
# ctest's json-v1 listing writes one key per line, keys sorted: a test's "name" line is followed by
# its "properties" (or the object's end), a property's "name" line by that property's "value".
fixture_setups=$(awk '
  pending != "" {
    if ($0 ~ /^[ \t]*"value"/) { if (pending == "FIXTURES_SETUP") print test }
    else test = pending
    pending = ""
  }
  /^[ \t]*"name" : "/ {
    pending = $0
    sub(/^[ \t]*"name" : "/, "", pending); sub(/",?[ \t]*$/, "", pending)
    gsub(/\\"/, "\"", pending); gsub(/\\\\/, "\\", pending)
  }' <<<"$listing")
# The names go through the environment: awk -v would read backslashes in them as escapes.
FIXTURE_SETUPS=$fixture_setups awk -v limit="$seconds" -v file="$log" '
  BEGIN { count = split(ENVIRON["FIXTURE_SETUPS"], kept, "\n"); for (i = 1; i <= count; i++) fixture[kept[i]] = 1 }
  /^[0-9]+\/[0-9]+ Test: / { name = $0; sub(/^[0-9]+\/[0-9]+ Test: /, "", name); next }
  /^Test time = / && name != "" {
    tests++
    cost = $4
    if (cost + 0 > limit + 0 && !(name in fixture)) {
      total += cost
      left_out++
      gsub(/[][\\.^$*+?()|{}]/, "\\\\&", name)
      expression = expression (expression == "" ? "" : "|") "^" name "$"
    }
    name = ""
  }
  END {
    if (tests == 0) { print file ": times no test" > "/dev/stderr"; exit 1 }
    printf "sanitizer run: %d of %d test cases left out (over %s s in the Release run, %.0f s there in all; fixture setups kept)\n", left_out, tests, limit, total > "/dev/stderr"
    # ctest -E needs an expression; one that matches no name leaves nothing out.
    print (expression == "" ? "^$" : expression)
  }' "$log"
