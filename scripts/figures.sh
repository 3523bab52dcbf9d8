#!/usr/bin/env bash
# Regenerates the bouncing-bar figure and error table of docs/results/bars.md (benchmarks.md
# §A, reference data, two periods, dt = h/(k c)) from fresh runs:
#   docs/bouncing-bar.png              u(0,t) of P1, P2, P3 at N = 40 against the exact one
#   docs/bouncing-bar-convergence.md   relative L2(0,2T) error of u(0,t), rates, penetration
# Needs a build (scripts/build.sh); intermediate files go to out/figures.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
run() { bash "$repo/scripts/freefem.sh" "$repo/edp/bouncing-bar.edp" "$@"; }

table="$repo/docs/bouncing-bar-convergence.md"
{
  echo "Bouncing bar (benchmarks.md §A, L = 10, E = 900, rho = 1, g = 10, h0 = 5), two periods,"
  echo "implicit NBM (Newmark beta = 1/4, gamma = 1/2), dt = h/(k c). Produced by \`bash scripts/figures.sh\`."
  echo
  echo "| order | N | dt | rel. L2(0,2T) error of u(0,t) | rate | rel. L2(0,2T;L2) error of u | max penetration | fallbacks |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$table"
for order in 1 2; do
  prev_e="" prev_n=""
  for N in 40 80 160 320; do
    out=$(run -order $order -N $N -out "bar-P$order-N$N")
    e=$(summary_value "$out" errL2u0)
    rate="-"
    [ -n "$prev_e" ] && rate=$(awk -v a="$prev_e" -v b="$e" -v m="$prev_n" -v n="$N" 'BEGIN { printf "%.2f", log(a / b) / log(n / m) }')
    echo "| P$order | $N | $(summary_value "$out" dt) | $e | $rate | $(summary_value "$out" errL2L2u) | $(summary_value "$out" maxPenetration) | $(summary_value "$out" fallbacks) |" >> "$table"
    prev_e=$e prev_n=$N
  done
done
cat "$table"

for order in 1 2 3; do run -order $order -N 40 -out "bar-P$order-N40" >/dev/null; done
plot_contact_end "$repo/docs/bouncing-bar.png" \
  "Bouncing bar (paper Fig. 1): height of the contact end, N = 40, dt = h/(k c)" \
  "'bar-P1-N40.csv' using 1:3 with lines lw 3 lc rgb 'black' title 'exact', \
  '' using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'NBM P1', \
  'bar-P2-N40.csv' using 1:2 with lines lw 1.5 lc rgb '#d62728' title 'NBM P2', \
  'bar-P3-N40.csv' using 1:2 with lines lw 1.5 lc rgb '#2ca02c' title 'NBM P3'"
echo "figures: wrote $repo/docs/bouncing-bar.png and $table"
