#!/usr/bin/env bash
# Time-step convergence of a quantity an example prints (`<key>=<value>`).
#   dt-convergence.sh <build> <repo> <script.edp> <key> <min-rate> "<dt list>" [script args...]
# Runs the script with -dt <dt> for each dt of the list (largest first) and
# requires the observed order log(e_i-1 / e_i) / log(dt_i-1 / dt_i) to be
# >= min-rate at every refinement. Prints the table.
set -u
build=$1 repo=$2 script=$3 key=$4 min_rate=$5 dts=$6
shift 6
run="$(dirname "$0")/run-freefem.sh"
tag=$(printf '%s' "dt-$(basename "$script" .edp)$*" | tr -c 'A-Za-z0-9.-' '_')
table=""
for dt in $dts; do
  out=$(bash "$run" "$build" "$repo" "$script" -dt "$dt" -out "$tag-dt$dt" -vtkFrames 0 "$@" 2>&1)
  code=$?
  if [ $code -ne 0 ]; then printf '%s\n' "$out" | tail -n 20; echo "FAIL: dt=$dt exited with $code"; exit 1; fi
  printf '%s\n' "$out" | grep -E "^[a-z-]+:" | sed "s/^/  dt=$dt  /"
  e=$(printf '%s\n' "$out" | grep -o "\b$key=[^ ]*" | tail -n 1 | cut -d= -f2)
  if [ -z "$e" ]; then echo "FAIL: no $key in the output"; exit 1; fi
  table="$table$dt $e"$'\n'
done
printf '%s' "$table" | awk -v key="$key" -v minr="$min_rate" -v args="$*" '
  { dt[NR] = $1; e[NR] = $2 }
  END {
    ok = 1
    printf "time-step convergence of %s (%s)\n%10s %14s %8s\n", key, args, "dt", key, "order"
    for (i = 1; i <= NR; i++) {
      r = (i > 1) ? log(e[i-1] / e[i]) / log(dt[i-1] / dt[i]) : 0
      printf "%10g %14.6g %8s\n", dt[i], e[i], (i > 1) ? sprintf("%.3f", r) : "-"
      if (i > 1 && !(r >= minr)) { print "FAIL: order " r " < " minr " from dt=" dt[i-1] " to dt=" dt[i]; ok = 0 }
    }
    exit ok ? 0 : 1
  }'
