#!/usr/bin/env bash
# The test files of lang_tests and runtime_tests are compiled in batches (a unity build,
# tests/CMakeLists.txt), so that a helper of one file must not meet a helper of the same name in
# another. Each file TESTS_DIR/{lang,runtime,cli}/**/NAME_test.cpp therefore holds its code in
# `namespace NAME_test {`, closed by its last line `}  // namespace NAME_test`. Fails naming each
# file that does not; then checks itself on a file that does and one that does not.
set -uo pipefail
tests=${1:?usage: test_namespaces_test.sh TESTS_DIR}

# Prints each FILE... that does not open and close its namespace.
unwrapped() {
  local file stem
  for file in "$@"; do
    stem=$(basename "$file" .cpp)
    if ! grep -qx "namespace $stem {" "$file" ||
      [ "$(grep -v '^[[:space:]]*$' "$file" | tail -n 1)" != "}  // namespace $stem" ]; then
      echo "$file"
    fi
  done
}

status=0
mapfile -t files < <(find "$tests/lang" "$tests/runtime" "$tests/cli" -name '*_test.cpp' | sort)
if [ "${#files[@]}" -eq 0 ]; then
  echo "FAIL: no test files under $tests/{lang,runtime,cli}"
  status=1
fi
bad=$(unwrapped "${files[@]}")
if [ -n "$bad" ]; then
  echo "$bad"
  echo "FAIL: the files above do not hold their code in a namespace named after the file: after the"
  echo "      #include lines write 'namespace NAME_test {', and end the file with '}  // namespace NAME_test'"
  status=1
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '#include <x>\n\nnamespace good_test {\n\nTEST_CASE("a") {}\n\n}  // namespace good_test\n\n' >"$dir/good_test.cpp"
printf '#include <x>\n\nnamespace {\n\nint f() { return 1; }\n\n}  // namespace\n' >"$dir/bad_test.cpp"
if [ "$(unwrapped "$dir/good_test.cpp" "$dir/bad_test.cpp")" != "$dir/bad_test.cpp" ]; then
  echo "FAIL: the check does not single out exactly the probe without its namespace"
  status=1
fi
exit $status
