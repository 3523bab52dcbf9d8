#!/usr/bin/env bash
# Runs an example whose last output line is "<name>: key=value key=value ..."
# and checks bounds on the values.
#   check-summary.sh <build> <repo> "<checks>" <script.edp> [script args...]
# <checks>: space-separated "key<=bound" or "key>=bound" (numbers, any format
# awk reads). Prints the line and one verdict per check; fails if a check
# fails, a key is missing or the script fails.
set -u
build=$1 repo=$2 checks=$3 script=$4
shift 4
out=$(bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$script" "$@" 2>&1)
status=$?
line=$(printf '%s\n' "$out" | grep -E '^[A-Za-z-]+: .*=' | tail -n 1)
if [ $status -ne 0 ] || [ -z "$line" ]; then
  printf '%s\n' "$out" | tail -n 20
  echo "FAIL: script exited with $status or printed no summary line"
  exit 1
fi
echo "$line"
awk -v line="$line" -v checks="$checks" 'BEGIN {
  n = split(line, kv, " ")
  for (i = 2; i <= n; ++i) { split(kv[i], p, "="); value[p[1]] = p[2]; seen[p[1]] = 1 }
  m = split(checks, c, " ")
  bad = 0
  for (i = 1; i <= m; ++i) {
    if (match(c[i], /<=|>=/) == 0) { print "FAIL: malformed check " c[i]; bad = 1; continue }
    key = substr(c[i], 1, RSTART - 1); op = substr(c[i], RSTART, 2); bound = substr(c[i], RSTART + 2) + 0
    if (!(key in seen)) { print "FAIL: " key " missing"; bad = 1; continue }
    v = value[key] + 0
    ok = (op == "<=") ? (v <= bound) : (v >= bound)
    printf "%s: %s = %.6g %s %.6g\n", ok ? "ok" : "FAIL", key, v, op, bound
    if (!ok) bad = 1
  }
  exit bad
}'
