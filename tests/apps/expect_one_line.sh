#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Runs a command that must fail on bad input: exit code CODE and exactly one line on stderr,
# matching REGEX (one line naming file and key; no third-party output).
# Usage: expect_one_line.sh CODE REGEX -- COMMAND [ARGS...]
set -u
code=$1 regex=$2
shift 2
[ "$1" = "--" ] && shift
tmp=$(mktemp -d) || exit 99
trap 'rm -rf "$tmp"' EXIT
"$@" >"$tmp/stdout" 2>"$tmp/stderr"
actual=$?
status=0
if [ "$actual" -ne "$code" ]; then
  echo "FAIL: exit code $actual, expected $code" >&2
  status=1
fi
lines=$(wc -l <"$tmp/stderr")
if [ "$lines" -ne 1 ]; then
  echo "FAIL: $lines lines on stderr, expected exactly 1" >&2
  status=1
fi
if ! grep -Eq -- "$regex" "$tmp/stderr"; then
  echo "FAIL: stderr does not match /$regex/" >&2
  status=1
fi
if [ "$status" -ne 0 ]; then
  echo "--- command: $*" >&2
  echo "--- stdout:" >&2; cat "$tmp/stdout" >&2
  echo "--- stderr:" >&2; cat "$tmp/stderr" >&2
fi
exit $status
