#!/usr/bin/env bash
# Paper Figure 1 with P2 and P4: the bouncing bar (benchmarks.md §A,
# reference data, two periods, dt = h/(k c)) at N = 40 elements, the height
# u(0,t) of the contact end of both against the exact solution.
#   bash scripts/figure1.sh       -> docs/bouncing-bar-p2-p4.png, errors on stdout
# Needs a build (scripts/build.sh): P4 is P4L from build/plugin/Element_PkL.so.
# Intermediate files (CSV time histories) go to out/figure1.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
work="$repo/out/figure1"
png="$repo/docs/bouncing-bar-p2-p4.png"
N=40
mkdir -p "$work" "$repo/docs"
cd "$work"
. "$repo/scripts/lib.sh"

printf '%-6s %4s %12s %28s %28s %16s\n' order N dt "rel. L2(0,2T) err u(0,t)" "rel. L2(0,2T;L2) err u" "max penetration"
for order in 2 4; do
  out=$(bash "$repo/scripts/freefem.sh" "$repo/edp/bouncing-bar.edp" -order $order -N $N \
        -vtkFrames 0 -out "bar-P$order-N$N")
  printf '%-6s %4s %12s %28s %28s %16s\n' "P$order" $N "$(summary_value "$out" dt)" "$(summary_value "$out" errL2u0)" \
    "$(summary_value "$out" errL2L2u)" "$(summary_value "$out" maxPenetration)"
done

plot_contact_end "$png" \
  "Bouncing bar (paper Fig. 1): height of the contact end, N = $N elements, dt = h/(k c)" \
  "'bar-P2-N$N.csv' using 1:3 with lines lw 3 lc rgb 'black' title 'exact', \
  '' using 1:2 with lines lw 1.5 lc rgb '#d62728' title 'NBM P2', \
  'bar-P4-N$N.csv' using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'NBM P4'"
echo "figure1: wrote $png"
