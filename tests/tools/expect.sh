#!/usr/bin/env bash
# expect.sh EXIT_CODE REGEX COMMAND [ARGS...]
# Runs COMMAND; passes when it exits with EXIT_CODE and its combined output
# matches the extended regular expression REGEX (empty REGEX: no check).
set -u
expected=$1 pattern=$2
shift 2
output=$("$@" 2>&1)
code=$?
echo "$output"
if [ "$code" != "$expected" ]; then
  echo "expect.sh: exit code $code, expected $expected: $*" >&2
  exit 1
fi
if [ -n "$pattern" ] && ! grep -qE -- "$pattern" <<<"$output"; then
  echo "expect.sh: output does not match /$pattern/: $*" >&2
  exit 1
fi
echo "expect.sh: exit $code and output as expected"
