#!/usr/bin/env bash
# ctest cannot run a doctest case whose name holds ';': doctest_discover_tests writes the name
# into a CMake list, where ';' separates elements, so the case's filter matches nothing and the
# test "passes" in 0 s without running. Fails on any TEST_CASE("...;...") under TESTS_DIR, naming
# file and line; then checks itself on a file that has one.
set -uo pipefail
tests=${1:?usage: test_names_test.sh TESTS_DIR}
pattern='TEST_CASE\("([^"\\]|\\.)*;'
status=0
if grep -rnE --include='*.cpp' --include='*.hpp' "$pattern" "$tests"; then
  echo "FAIL: the test cases above have ';' in their names, which ctest never runs: write ',' or ':' instead"
  status=1
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf 'TEST_CASE("a; b") {}\nTEST_CASE("a, b") {}\n' >"$dir/probe_test.cpp"
if [ "$(grep -rcE --include='*.cpp' "$pattern" "$dir")" != "$dir/probe_test.cpp:1" ]; then
  echo "FAIL: the check does not find exactly the one name with ';' in its probe"
  status=1
fi
exit $status
