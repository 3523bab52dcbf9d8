#!/usr/bin/env bash
# Free flight of the bouncing plate before the first impact: the centre of
# mass must follow the parabola of gravity, y_com(t) = y_com(0) - g t^2/2 and
# v_com = -g t, to 1e-10 (NBM test functions contain the rigid translations,
# and average acceleration integrates a constant acceleration exactly).
#   plate-free-flight.sh <build> <repo> <g> [bouncing-plate.edp args...]
# The run stops at 0.9 of the fall time sqrt(2 h0/g) of the default h0 = 0.1.
set -eu
build=$1 repo=$2 g=$3
shift 3
tag=$(printf '%s' "free-flight$*" | tr -c 'A-Za-z0-9.-' '_')
T=$(awk -v g="$g" 'BEGIN { printf "%.6f", 0.9 * sqrt(2 * 0.1 / g) }')
bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/edp/bouncing-plate.edp" \
  -grav "$g" -T "$T" -vtkFrames 0 -snapshots 0 -out "$tag" "$@" | tail -n 1
awk -F, -v g="$g" '
  NR == 2 { y0 = $2 }
  NR >= 2 {
    dy = $2 - (y0 - g * $1 * $1 / 2); dv = $3 + g * $1
    if (dy < 0) dy = -dy; if (dv < 0) dv = -dv
    if (dy > ey) ey = dy; if (dv > ev) ev = dv
    if ($7 != 0) { print "FAIL: contact closed at t = " $1; bad = 1 }
    n++
  }
  END {
    printf "free flight: %d steps, max |y_com - parabola| = %.3g, max |v_com + g t| = %.3g\n", n, ey, ev
    if (n < 10) { print "FAIL: too few steps"; exit 1 }
    if (ey > 1e-10 || ev > 1e-10) { print "FAIL: tolerance 1e-10 exceeded"; exit 1 }
    exit bad
  }' "$tag.csv"
