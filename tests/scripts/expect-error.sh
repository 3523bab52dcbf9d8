#!/usr/bin/env bash
# A bad-input test: the script must stop with a FreeFEM ExecError (not a crash,
# not a hang, not success) whose message matches the expected pattern.
#   expect-error.sh <build-dir> <repo-dir> <regex> <script.edp> [args...]
set -u
build=$1 repo=$2 pattern=$3 script=$4
shift 4
out=$(timeout 120 bash "$(dirname "$0")/run-freefem.sh" "$build" "$repo" "$script" "$@" 2>&1)
code=$?
printf '%s\n' "$out" | tail -n 15
if [ $code -eq 0 ]; then echo "FAIL: the script succeeded, expected an ExecError"; exit 1; fi
if [ $code -eq 124 ]; then echo "FAIL: the script hung (timeout)"; exit 1; fi
if [ $code -gt 128 ]; then echo "FAIL: the script crashed (signal $((code - 128)))"; exit 1; fi
if ! printf '%s\n' "$out" | grep -q "Exec error"; then
  echo "FAIL: exit code $code without an ExecError"; exit 1
fi
if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  echo "FAIL: the error message does not match /$pattern/"; exit 1
fi
echo "OK: ExecError matching /$pattern/"
