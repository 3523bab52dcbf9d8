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
value() { printf '%s\n' "$1" | grep -o "\b$2=[^ ]*" | tail -n 1 | cut -d= -f2; }

printf '%-6s %4s %12s %28s %28s %16s\n' order N dt "rel. L2(0,2T) err u(0,t)" "rel. L2(0,2T;L2) err u" "max penetration"
for order in 2 4; do
  out=$(bash "$repo/scripts/freefem.sh" "$repo/edp/bouncing-bar.edp" -order $order -N $N \
        -vtkFrames 0 -out "bar-P$order-N$N")
  printf '%-6s %4s %12s %28s %28s %16s\n' "P$order" $N "$(value "$out" dt)" "$(value "$out" errL2u0)" \
    "$(value "$out" errL2L2u)" "$(value "$out" maxPenetration)"
done

gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1100,800 font ',11'
set output '$png'
set multiplot layout 2,1 title 'Bouncing bar (paper Fig. 1): height of the contact end, N = $N elements, dt = h/(k c)'
set xlabel 't'; set ylabel 'u(0,t)'; set grid; set autoscale xfix
set key outside top center horizontal
curves = "'bar-P2-N$N.csv' using 1:3 with lines lw 3 lc rgb 'black' title 'exact', \
  '' using 1:2 with lines lw 1.5 lc rgb '#d62728' title 'NBM P2', \
  'bar-P4-N$N.csv' using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title 'NBM P4'"
plot @curves
set title 'zoom: first contact, flight with the bar vibrating, second contact'
set xrange [0.8:4.6]; set yrange [-0.2:4.8]
unset key
plot @curves
unset multiplot
GP
echo "figure1: wrote $png"
