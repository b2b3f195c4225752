#!/usr/bin/env bash
# Runs a command that must fail: checks its exit status and that stderr contains a text.
#   expect_failure.sh EXPECTED_STATUS EXPECTED_STDERR_TEXT COMMAND [ARGS...]
# EXPECTED_STATUS "nonzero" accepts any failing status (but not a crash by signal).
set -uo pipefail
expected_status=$1 expected_text=$2
shift 2
stderr_file=$(mktemp)
trap 'rm -f "$stderr_file"' EXIT

"$@" 2>"$stderr_file"
status=$?
cat "$stderr_file"
if [ "$status" -eq 0 ]; then
  echo "FAIL: exited 0"
  exit 1
fi
if [ "$status" -ge 128 ]; then
  echo "FAIL: killed by signal $((status - 128))"
  exit 1
fi
if [ "$expected_status" != nonzero ] && [ "$status" -ne "$expected_status" ]; then
  echo "FAIL: exit status $status, expected $expected_status"
  exit 1
fi
if ! grep -qF -- "$expected_text" "$stderr_file"; then
  echo "FAIL: stderr does not contain '$expected_text'"
  exit 1
fi
echo "PASS: exit $status, stderr contains '$expected_text'"
