#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Runs a command and checks its exit code and a regex on one of its output streams.
# Usage: expect_exit.sh CODE stdout|stderr REGEX -- COMMAND [ARGS...]
set -u
code=$1 stream=$2 regex=$3
shift 3
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
if ! grep -Eq -- "$regex" "$tmp/$stream"; then
  echo "FAIL: $stream does not match /$regex/" >&2
  status=1
fi
if [ "$status" -ne 0 ]; then
  echo "--- command: $*" >&2
  echo "--- stdout:" >&2; cat "$tmp/stdout" >&2
  echo "--- stderr:" >&2; cat "$tmp/stderr" >&2
fi
exit $status
