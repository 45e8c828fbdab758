#!/usr/bin/env bash
# sanitizer_excludes.sh leaves out exactly the cases whose Release time (ctest's LastTest.log)
# exceeds the limit, names with spaces and regular-expression characters matched whole, and
# refuses a missing or empty log.
set -uo pipefail
script=${1:?usage: sanitizer_excludes_test.sh PATH/TO/sanitizer_excludes.sh}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

block() {  # block I NAME SECONDS: one case's record in ctest's LastTest.log
  printf '%s/5 Testing: %s\n%s/5 Test: %s\nCommand: "x"\nOutput:\n----------\nTest time = %s sec\n\n' \
    "$1" "$2" "$1" "$2" "$3"
  printf -- '----------\nTest Passed.\n"%s" end time: Nov 29 04:00 UTC\n"%s" time elapsed: 00:00:00\n----------\n\n' "$2" "$2"
}
{
  echo "Start testing: Nov 29 04:00 UTC"
  block 1 "runtime:a cheap case" "   0.20"
  block 2 "runtime:diagnose, harmonic: a slow case (#24) with 1e-9" "  31.50"
  block 3 "lang:exactly at the limit" "   5.00"
  block 4 "runtime:a case a little over it [x]" "   5.01"
  echo "End testing: Nov 29 04:01 UTC"
} >"$dir/costs"
expression=$("$script" "$dir/costs" 5 2>"$dir/err") || fail "exit status $? on a valid file"
expected='^runtime:diagnose, harmonic: a slow case \(#24\) with 1e-9$|^runtime:a case a little over it \[x\]$'
[ "$expression" = "$expected" ] || fail "expression '$expression', expected '$expected'"
grep -q "2 of 4 test cases left out" "$dir/err" || fail "summary: $(cat "$dir/err")"
# The expression, given to grep -E as ctest uses it, matches the slow names and no other.
names=$(printf '%s\n' "runtime:a cheap case" "runtime:diagnose, harmonic: a slow case (#24) with 1e-9" \
  "lang:exactly at the limit" "runtime:a case a little over it [x]" "runtime:a case a little over it x")
matched=$(grep -cE -- "$expression" <<<"$names")
[ "$matched" -eq 2 ] || fail "the expression matches $matched names, not 2"

expression=$("$script" "$dir/costs" 100 2>/dev/null) || fail "exit status $? with nothing over the limit"
[ "$expression" = '^$' ] || fail "nothing over the limit gives '$expression', expected '^\$'"
! grep -qE -- "$expression" <<<"$names" || fail "'^\$' matches a name"

: >"$dir/empty"
"$script" "$dir/empty" 5 >/dev/null 2>&1 && fail "an empty log is accepted"
"$script" "$dir/missing" 5 >/dev/null 2>&1 && fail "a missing log is accepted"
[ $failures -eq 0 ] && echo "sanitizer_excludes: 6 checks passed"
exit $failures
