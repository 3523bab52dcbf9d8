#!/usr/bin/env bash
# scripts/plate-dispersion.sh on hand-made probe histories whose arrival and
# shape errors are known in closed form.
#   plate-dispersion.sh <repo>
# Reference (step 0.01, h0 = 1, g = 1/2: J = sqrt(2 g h0) = 1): the probe
# comes down at speed 1, lands at t = 1 (u = -1), stays until t = 2, leaves at
# speed 1. Its kinks as the script reads them: t_td = 1 (first sample on the
# ground), t_lo = 2.01 (first sample off it), w = (2.01 - 1)/2 = 0.505.
#  (a) the reference delayed by 0.05 everywhere: arrival 0.05/w at both
#      kinks, shapes 0 (a pure delay is all arrival);
#  (b) the reference with a trailing oscillation after the lift-off:
#      velocity 1 + A sin(2 pi (t - 2)/P) on (2, 2 + m P), A = 0.2, P = 0.04,
#      m = 5. No shift does better than none (a shift s adds a stretch of
#      misfit 1 +- A > 2A), so arrival 0 and shape m int_0^P |A sin| =
#      2 m A P/pi; the sine changes sign at the steps' ends only, so the
#      measure's mean velocities per step lose nothing of it. Its part
#      after t* = 2.01 leaves out the step (2, 2.01): A P/(2 pi) less.
# Shapes in units of w.
set -eu
repo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
header='t,y_com,v_com,u_probe,lambda_total,penetration_max,n_active,e_kin,e_el,e_load,e_tot'
# probe <t>: the reference displacement; trail <t>: case (b).
awk -v header="$header" '
  function probe(t) { return t <= 1 ? -t : (t <= 2 ? -1 : -1 + (t - 2)) }
  function trail(t) {
    if (t <= 2 || t >= 2.2) return probe(t)
    return probe(t) + 0.2 * 0.04 / (2 * pi) * (1 - cos(2 * pi * (t - 2) / 0.04))
  }
  function row(f, t, u) { printf "%.10g,0,0,%.10g,0,0,0,0,0,0,0\n", t, u > f }
  BEGIN {
    pi = atan2(0, -1)
    print header > "ref.csv"; print header > "delayed.csv"; print header > "trail.csv"
    for (i = 0; i <= 350; i++) {
      t = i / 100
      row("ref.csv", t, probe(t))
      row("delayed.csv", t, t < 0.05 ? 0 : probe(t - 0.05))
      row("trail.csv", t, trail(t))
    }
  }'
window=$(bash "$repo/scripts/plate-dispersion.sh" -window ref.csv 1)
echo "kinks of the reference: $window (expected 1,2.01)"
[ "$window" = "1,2.01" ] || { echo "FAIL: kink times"; exit 1; }
bad=0
check() {  # check <case> <got> <expected>: equal to 1e-6
  echo "$1: got $2, expected $3"
  awk -F, -v a="$2" -v b="$3" 'BEGIN {
    n = split(a, x, ","); m = split(b, y, ",")
    if (n != m) exit 1
    for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 1e-6) exit 1 }
  }' || { echo "FAIL: $1"; bad=1; }
}
check delayed "$(bash "$repo/scripts/plate-dispersion.sh" delayed.csv ref.csv 1 0.5)" \
  "$(awk 'BEGIN { w = 0.505; printf "%.9g,0,%.9g,0,0", 0.05 / w, 0.05 / w }')"
check trail "$(bash "$repo/scripts/plate-dispersion.sh" trail.csv ref.csv 1 0.5)" \
  "$(awk 'BEGIN { w = 0.505; pi = atan2(0, -1); s = 2 * 5 * 0.2 * 0.04 / pi
                  printf "0,0,0,%.9g,%.9g", s / w, (s - 0.2 * 0.04 / (2 * pi)) / w }')"
# A reference that never leaves the ground is refused.
awk -v header="$header" 'BEGIN { print header; for (i = 0; i <= 350; i++) { t = i / 100; printf "%g,0,0,%g,0,0,0,0,0,0,0\n", t, t <= 1 ? -t : -1 } }' > stuck.csv
if bash "$repo/scripts/plate-dispersion.sh" delayed.csv stuck.csv 1 0.5 2> err.txt; then
  echo "FAIL: a reference without lift-off was accepted"; bad=1
else
  echo "refused as expected: $(cat err.txt)"
fi
exit $bad
