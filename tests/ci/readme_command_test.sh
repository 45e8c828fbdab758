#!/usr/bin/env bash
# .ci/readme-command must fail when any command of a README line fails, not only the last one,
# run the line from README's folder, and refuse a README without the command asked for.
set -uo pipefail
runner=${1:?usage: readme_command_test.sh PATH/TO/.ci/readme-command [PROJECT/README.md]}
project_readme=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
expect() {  # expect STATUS N: the status of command N of $dir/README.md
  "$runner" "$2" "$dir/README.md" >"$dir/out" 2>&1
  local got=$?
  if [ "$got" -ne "$1" ]; then
    echo "FAIL: command $2 of:"; cat "$dir/README.md"; echo "exited $got, expected $1; output:"; cat "$dir/out"
    failures=$((failures + 1))
  fi
}
printf '# t\n```sh\ntrue && test -f here.txt\nfalse && true && true\n```\n\n```sh\ntrue\n```\n' >"$dir/README.md"
touch "$dir/here.txt"
expect 0 1   # runs in README's folder (here.txt is found there)
expect 1 2   # the first command of the && list fails: the line fails
expect 2 3   # only the opening block counts: no command 3
printf '```sh\ntrue && exit 7 && true\n```\n' >"$dir/README.md"
expect 7 1   # the failing command's own status
checks=4
if [ -n "$project_readme" ]; then  # the project's README opens with exactly two commands
  checks=$((checks + 1))
  cp "$project_readme" "$dir/README.md"
  expect 2 3
fi
echo "$((checks - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
