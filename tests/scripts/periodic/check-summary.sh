#!/usr/bin/env bash
# Runs an example whose last output line is "<name>: key=value key=value ..."
# (<name>: letters, digits, dashes)
# and checks bounds on the values.
#   check-summary.sh <build> <repo> "<checks>" <script.edp> [script args...]
# <checks>: space-separated "key<=bound" or "key>=bound" (numbers, any format
# awk reads). Prints the line and one verdict per check; fails if a check
# fails, a key is missing or the script fails.
set -u
build=$1 repo=$2 checks=$3 script=$4
. "$repo/scripts/lib.sh"
shift 4
out=$(bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$script" "$@" 2>&1)
status=$?
line=$(printf '%s\n' "$out" | grep -E '^[A-Za-z0-9-]+: .*=' | tail -n 1)
if [ $status -ne 0 ] || [ -z "$line" ]; then
  printf '%s\n' "$out" | tail -n 20
  echo "FAIL: script exited with $status or printed no summary line"
  exit 1
fi
echo "$line"
bad=0
for check in $checks; do
  if ! [[ $check =~ ^([^<>]*)(<=|>=)(.*)$ ]]; then
    echo "FAIL: malformed check $check"; bad=1; continue
  fi
  key=${BASH_REMATCH[1]} op=${BASH_REMATCH[2]} bound=${BASH_REMATCH[3]}
  value=$(summary_value "$line" "$key")
  if [ -z "$value" ]; then
    echo "FAIL: $key missing"; bad=1; continue
  fi
  awk -v key="$key" -v v="$value" -v op="$op" -v b="$bound" 'BEGIN {
    v += 0; b += 0; ok = (op == "<=") ? (v <= b) : (v >= b)
    printf "%s: %s = %.6g %s %.6g\n", ok ? "ok" : "FAIL", key, v, op, b
    exit !ok
  }' || bad=1
done
exit $bad
