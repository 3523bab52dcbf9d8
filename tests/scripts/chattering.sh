#!/usr/bin/env bash
# Chattering counts: (1) scripts/plate-metrics.sh on a hand-made contact
# history whose counts and distances are known; (2) the bouncing bar (NBM, P1 and the
# massless boundary) touches down exactly once per impact: one contact
# interval of the contact end in each window around the exact contact phases
# [t1, t2] and [t3, t4] of benchmarks.md §A (reference data: [1, 5/3] and
# [11/3, 13/3], windows widened by 1/3).
#   chattering.sh <build> <repo>
set -eu
build=$1 repo=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# (1) Two nodes, two impacts: impact 1: node0 touches twice, node1 once;
# impact 2: node1 once. Mean over (node, impact) pairs (2+1+1)/3, max 2.
# Against a reference 0.5 higher in y_com and 0 in u_probe (the run has
# u_probe = t): trapezoidal L2 distances sqrt(7/4) and sqrt(115.5) over (0, 7),
# sqrt(3/4) and sqrt(9.5) over (0, 3).
printf 't,node0,node1\n0,0,0\n1,1,0\n2,0,1\n3,1,1\n4,0,0\n5,0,0\n6,0,1\n7,0,0\n' > c.csv
header='t,y_com,v_com,u_probe,lambda_total,penetration_max,n_active,e_kin,e_el,e_load,e_tot'
echo "$header" > r.csv
echo "$header" > ref.csv
for t in 0 1 2 3 4 5 6 7; do
  echo "$t,1,0,$t,0,0.$t,0,0,0,0,-0.$t" >> r.csv
  echo "$t,1.5,0,0,0,0,0,0,0,0,0" >> ref.csv
done
got=$(bash "$repo/scripts/plate-metrics.sh" r.csv c.csv ref.csv 1 3)
want=$(awk 'BEGIN { printf "0.7,-0.7,0.7,1.33333,2,2,%.6g,%.6g,%.6g,%.6g", sqrt(7 / 4), sqrt(115.5), sqrt(3 / 4), sqrt(9.5) }')
echo "plate-metrics on the hand-made history: $got (expected $want)"
[ "$got" = "$want" ] || { echo "FAIL: metrics differ"; exit 1; }

# (2) The bar.
for mass in consistent redistributed; do
  bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/edp/bouncing-bar.edp" \
    -N 80 -mass $mass -vtkFrames 0 -out bar | tail -n 1
  awk -F, -v mass=$mass '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == "active") col = i; next }
    { a = $col; t = $1
      if (t > 2.0 / 3 && t < 2) { if (a == 1 && prev == 0) n1++ }
      if (t > 10.0 / 3 && t < 14.0 / 3) { if (a == 1 && prev == 0) n2++ }
      prev = a }
    END { printf "bar (%s mass): contact intervals in the first impact %d, in the second %d\n", mass, n1, n2
          exit (n1 == 1 && n2 == 1) ? 0 : 1 }' bar.csv || { echo "FAIL: the bar chatters"; exit 1; }
done
