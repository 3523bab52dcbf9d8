#!/usr/bin/env bash
# Energy of the bouncing plate over T = 1 (three bounces and more):
# - massless boundary (mass = "redistributed"): the largest energy error,
#   relative to m g h0, decreases at every refinement of dt (1e-3, 5e-4,
#   2.5e-4; observed rates printed) and is below 0.5% at the default dt 2.5e-4;
# - the paper's NBM (consistent mass) loses the contact nodes' kinetic energy
#   at every touch-down: the loss per impact is reported, not asserted.
#   plate-energy.sh <build> <repo> [bouncing-plate.edp args...]
set -eu
build=$1 repo=$2
. "$repo/scripts/lib.sh"
shift 2
run() { bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/edp/bouncing-plate.edp" \
          -T 1 -vtkFrames 0 -snapshots 0 "$@" | grep '^bouncing-plate:'; }
drift() {  # largest |E(t) - E(0)| / mgh0 of a CSV
  awk -F, -v m="$2" 'NR == 2 { e0 = $11 } NR > 1 { d = $11 - e0; if (d < 0) d = -d; if (d > x) x = d }
                     END { printf "%.6g", x / m }' "$1"
}
table=""
for dt in 1e-3 5e-4 2.5e-4; do
  line=$(run -mass redistributed -dt $dt -out energy-massless-$dt "$@")
  mgh0=$(summary_value "$line" mgh0)
  table="$table$dt $(drift energy-massless-$dt.csv "$mgh0")
"
done
printf '%s' "$table" | awk '
  { dt[NR] = $1; d[NR] = $2 }
  END {
    print "massless boundary: max |E - E0| / (m g h0) over T = 1"
    for (i = 1; i <= NR; i++)
      printf "  dt = %-8s %.4g%s\n", dt[i], d[i], (i > 1 ? sprintf("   rate %.2f", log(d[i-1] / d[i]) / log(dt[i-1] / dt[i])) : "")
    for (i = 2; i <= NR; i++) if (!(d[i] < d[i-1])) { print "FAIL: the energy error does not decrease with dt"; exit 1 }
    if (!(d[NR] < 0.005)) { print "FAIL: energy error " d[NR] " >= 0.5% at the default dt"; exit 1 }
  }'
line=$(run -mass consistent -out energy-consistent "$@")
mgh0=$(summary_value "$line" mgh0)
awk -F, -v m="$mgh0" '
  NR == 1 { next }
  { if (NR == 2) e0 = $11; if ($7 > 0 && !c) impacts++; c = ($7 > 0); e = $11 }
  END { printf "paper NBM (consistent mass): energy lost over T = 1: %.3g of m g h0 in %d touch-downs, %.3g per touch-down\n",
               (e0 - e) / m, impacts, (e0 - e) / m / impacts }' energy-consistent.csv
