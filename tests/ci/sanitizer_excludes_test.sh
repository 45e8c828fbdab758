#!/usr/bin/env bash
# sanitizer_excludes.sh leaves out exactly the cases whose Release time (ctest's LastTest.log)
# exceeds the limit, names with spaces and regular-expression characters matched whole, except
# the sanitizer build's fixture setups, and refuses a missing or empty log or an unlisted build.
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
  block 5 "fixture_build" "  40.00"
  block 6 'a "quoted" setup \ with a backslash' "  12.00"
  echo "End testing: Nov 29 04:01 UTC"
} >"$dir/costs"
# The sanitizer build, as ctest reads it: fixture_build sets up the fixture the second case needs
# (ctest -E would drop it and fail that case); a setup only by its name's likeness is not one; a
# setup's name with quotes and a backslash (escaped in ctest's JSON) is read back as it is.
mkdir "$dir/build"
cat >"$dir/build/CTestTestfile.cmake" <<'TESTS'
add_test([=[runtime:a cheap case]=] "true")
add_test([=[runtime:diagnose, harmonic: a slow case (#24) with 1e-9]=] "true")
set_tests_properties([=[runtime:diagnose, harmonic: a slow case (#24) with 1e-9]=] PROPERTIES FIXTURES_REQUIRED "built" LABELS "FIXTURES_SETUP")
add_test([=[lang:exactly at the limit]=] "true")
add_test([=[runtime:a case a little over it [x]]=] "true")
add_test([=[fixture_build]=] "true")
set_tests_properties([=[fixture_build]=] PROPERTIES FIXTURES_SETUP "built")
add_test([=[a "quoted" setup \ with a backslash]=] "true")
set_tests_properties([=[a "quoted" setup \ with a backslash]=] PROPERTIES FIXTURES_SETUP "other")
TESTS
expression=$("$script" "$dir/costs" 5 "$dir/build" 2>"$dir/err") || fail "exit status $? on a valid file"
expected='^runtime:diagnose, harmonic: a slow case \(#24\) with 1e-9$|^runtime:a case a little over it \[x\]$'
[ "$expression" = "$expected" ] || fail "expression '$expression', expected '$expected'"
grep -q "2 of 6 test cases left out" "$dir/err" || fail "summary: $(cat "$dir/err")"
# The expression, given to grep -E as ctest uses it, matches the slow names and no other.
names=$(printf '%s\n' "runtime:a cheap case" "runtime:diagnose, harmonic: a slow case (#24) with 1e-9" \
  "lang:exactly at the limit" "runtime:a case a little over it [x]" "runtime:a case a little over it x")
matched=$(grep -cE -- "$expression" <<<"$names")
[ "$matched" -eq 2 ] || fail "the expression matches $matched names, not 2"

expression=$("$script" "$dir/costs" 100 "$dir/build" 2>/dev/null) || fail "exit status $? with nothing over the limit"
[ "$expression" = '^$' ] || fail "nothing over the limit gives '$expression', expected '^\$'"
! grep -qE -- "$expression" <<<"$names" || fail "'^\$' matches a name"

: >"$dir/empty"
"$script" "$dir/empty" 5 "$dir/build" >/dev/null 2>&1 && fail "an empty log is accepted"
"$script" "$dir/missing" 5 "$dir/build" >/dev/null 2>&1 && fail "a missing log is accepted"
"$script" "$dir/costs" 5 >/dev/null 2>&1 && fail "no sanitizer build is accepted"
"$script" "$dir/costs" 5 "$dir/missing" >/dev/null 2>&1 && fail "a build ctest cannot list is accepted"
mkdir "$dir/unconfigured"
"$script" "$dir/costs" 5 "$dir/unconfigured" >/dev/null 2>&1 && fail "a build with no tests is accepted"
[ $failures -eq 0 ] && echo "sanitizer_excludes: 9 checks passed"
exit $failures
