#!/usr/bin/env bash
# A script that must stop by itself with a given exit code (FreeFEM `exit(n)`,
# not an ExecError, not a crash) and print a message matching a pattern.
#   expect-exit.sh <code> <regex> <build-dir> <repo-dir> <script.edp> [args...]
set -u
code=$1 pattern=$2 build=$3 repo=$4 script=$5
shift 5
out=$(timeout 120 bash "$(dirname "$0")/run-freefem.sh" "$build" "$repo" "$script" "$@" 2>&1)
got=$?
printf '%s\n' "$out" | tail -n 8
if [ $got -ne "$code" ]; then echo "FAIL: exit code $got, expected $code"; exit 1; fi
if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  echo "FAIL: the output does not match /$pattern/"; exit 1
fi
echo "OK: exit code $code and a message matching /$pattern/"
