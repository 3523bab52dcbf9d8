#!/usr/bin/env bash
# Mesh-convergence test of an example script.
#   convergence.sh <build> <repo> <script.edp> <keys> <max-final> "<N list>" [script args...]
# Runs the script for each N (dt follows the script's default dt = h/(k c)),
# reads `<key>=<value>` from its output for each comma-separated key, requires
# every error to decrease at every refinement and the finest value of the
# first key to be <= max-final (inf: no bound), and prints the table with
# the observed rates and the least-squares rate. With NBM_MIN_RATE set in the
# environment, the least-squares rate of the first key must be >= it too.
set -u
build=$1 repo=$2 script=$3 keys=$4 max_final=$5 Ns=$6
shift 6
run="$(dirname "$0")/run-freefem.sh"
table=$(mktemp)
trap 'rm -f "$table"' EXIT
# Output files are named after the script and its arguments: tests running in
# parallel never write the same file.
tag=$(printf '%s' "$(basename "$script" .edp)$*" | tr -c 'A-Za-z0-9.-' '_')
for N in $Ns; do
  out=$(bash "$run" "$build" "$repo" "$script" -N "$N" -out "conv-$tag-N$N" "$@" 2>&1)
  code=$?
  if [ $code -ne 0 ]; then printf '%s\n' "$out" | tail -n 20; echo "FAIL: N=$N exited with $code"; exit 1; fi
  printf '%s\n' "$out" | grep -E "^[a-z-]+:" | sed "s/^/  N=$N  /"
  row="$N"
  for key in ${keys//,/ }; do
    e=$(printf '%s\n' "$out" | grep -o "\b$key=[^ ]*" | tail -n 1 | cut -d= -f2)
    if [ -z "$e" ]; then echo "FAIL: no $key in the output"; exit 1; fi
    row="$row $e"
  done
  echo "$row" >> "$table"
done
awk -v keys="$keys" -v maxf="$max_final" -v minrate="${NBM_MIN_RATE:-}" -v args="$*" '
  BEGIN { nk = split(keys, key, ",") }
  { N[NR] = $1; for (k = 1; k <= nk; k++) e[NR, k] = $(k + 1) }
  END {
    ok = 1
    for (k = 1; k <= nk; k++) {
      printf "convergence of %s (%s)\n%8s %14s %8s\n", key[k], args, "N", key[k], "rate"
      sx = sy = sxx = sxy = 0
      for (i = 1; i <= NR; i++) {
        rate = (i > 1) ? log(e[i-1, k] / e[i, k]) / log(N[i] / N[i-1]) : 0
        printf "%8d %14.6g %8s\n", N[i], e[i, k], (i > 1) ? sprintf("%.3f", rate) : "-"
        if (i > 1 && !(e[i, k] < e[i-1, k])) { print "FAIL: " key[k] " did not decrease from N=" N[i-1] " to N=" N[i]; ok = 0 }
        x = log(N[i]); y = log(e[i, k]); sx += x; sy += y; sxx += x*x; sxy += x*y
      }
      fitted = -(NR * sxy - sx * sy) / (NR * sxx - sx * sx)
      printf "fitted rate of %s: %.3f\n", key[k], fitted
      if (k == 1 && minrate != "" && !(fitted >= minrate)) { print "FAIL: fitted rate of " key[1] " = " fitted " < " minrate; ok = 0 }
    }
    if (maxf != "inf" && !(e[NR, 1] <= maxf)) { print "FAIL: finest " key[1] " = " e[NR, 1] " > " maxf; ok = 0 }
    exit ok ? 0 : 1
  }' "$table"
