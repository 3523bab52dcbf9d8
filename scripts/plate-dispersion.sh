#!/usr/bin/env bash
# Dispersion measure of one bouncing-plate run over the first impact, against
# a reference run (both CSVs as written by plate-setup.idp; flat ground y = 0),
# the plate's version of the kink metrics of edp/compare-bar.edp (issue 16,
# item 4). Printed as one comma-separated line:
#   touchdown_arrival, touchdown_shape, liftoff_arrival, liftoff_shape,
#   liftoff_shape_after
#   plate-dispersion.sh <run.csv> <reference.csv> <h0> <g>
# and, for the captions and plots, the kink times of the reference, t_td,t_lo:
#   plate-dispersion.sh -window <reference.csv> <h0>
#
# The probe (u_probe: vertical displacement of the bottom-middle node) sees
# two sharp events in the first impact, both jumps of its velocity by about
# J = sqrt(2 g h0) (exactly so in the uniaxial-strain solution of a plate
# much wider than high): the touch-down, and the lift-off, which is the
# arrival of the compression front reflected at the top face: it has crossed
# the plate twice through the mesh, the signature of dispersion (the "wave"
# kinks of the bar). Their times are read from the reference: t_td, the
# first sample with the probe on the ground (h0 + u_probe <= 1e-12 h0),
# t_lo, the first sample after it with the probe off the ground; w =
# (t_lo - t_td)/2, half the spacing of the kinks as for the bar (about
# H/c_p, the crossing time of the plate). Around each kink t*, over
# W = [t* - w, t* + w] and on the run's own steps t_n (within W):
#   S(s)     = sum_n |du_n - (u_ref(t_{n+1} - s) - u_ref(t_n - s))|
#              = int_W |v_h(t) - v_ref(t - s)| dt with v the mean velocity of
#              each step (exact for Newmark's trapezoidal rule), u_ref
#              interpolated linearly; independent of a constant offset such
#              as a penetration;
#   arrival  delta = the shift s minimising S(s), |s| <= w/2 on a grid of
#              half the reference's step (positive: the run is late);
#   shape    S(delta) / J: what remains after the best shift (0 for a front
#              as sharp as the reference's, the area of a smeared front or of
#              the trailing oscillations otherwise); for the lift-off also its
#              part after t* (the steps whose midpoint is past t*): the front
#              and its trail, without the contact node's motion while closed
#              (Nitsche and penalty let it oscillate in the contact spring),
# all in units of w. The window ends at t_lo + w: one crossing after the
# lift-off, over which the reference's own error is checked by
# scripts/compare-plate.sh (a run on lc/2, dt/2 measured the same way).
set -eu
if [ "$1" = -window ]; then
  mode=window run=/dev/null ref=$2 h0=$3 g=0
else
  mode=measure run=$1 ref=$2 h0=$3 g=$4
fi
awk -F, -v mode="$mode" -v h0="$h0" -v g="$g" '
  function uref(t,   lo, hi, mid) {  # linear interpolation of the reference probe
    if (t <= rt[1]) return ru[1]
    if (t >= rt[nr]) return ru[nr]
    lo = 1; hi = nr
    while (hi - lo > 1) { mid = int((lo + hi) / 2); if (rt[mid] <= t) lo = mid; else hi = mid }
    return ru[lo] + (t - rt[lo]) / (rt[hi] - rt[lo]) * (ru[hi] - ru[lo])
  }
  function kink(c,   a, b, k, nk, ds, s, sum, n, n0, n1, best, bests) {  # sets delta, shape, after
    a = c - w; b = c + w
    if (a - w / 2 < rt[1] || b + w / 2 > rt[nr] || b > t[nn]) {
      print "plate-dispersion: the runs end before the first impact window (t <= " b + w / 2 ")" > "/dev/stderr"
      exit 2
    }
    for (n0 = 1; t[n0] < a; n0++) {}
    for (n1 = n0; n1 < nn && t[n1 + 1] <= b; n1++) {}  # steps n0 .. n1 - 1 lie in W
    ds = (rt[2] - rt[1]) / 2; nk = int(w / 2 / ds)
    best = -1
    for (k = -nk; k <= nk; k++) {
      s = k * ds; sum = 0
      for (n = n0; n < n1; n++) sum += misfit(n, s)
      if (best < 0 || sum < best || (sum == best && abs_(s) < abs_(bests))) { best = sum; bests = s }
    }
    after = 0
    for (n = n0; n < n1; n++) if (t[n] + t[n + 1] > 2 * c) after += misfit(n, bests)
    delta = bests / w; shape = best / J / w; after = after / J / w
  }
  # |du_n - du_ref| over step n of the run, the reference shifted by s.
  function misfit(n, s) { return abs_(u[n + 1] - u[n] - (uref(t[n + 1] - s) - uref(t[n] - s))) }
  function abs_(x) { return x < 0 ? -x : x }
  FNR == 1 { next }
  FILENAME == ARGV[1] { rt[++nr] = $1; ru[nr] = $4; next }
  { t[++nn] = $1; u[nn] = $4 }
  END {
    for (i = 1; i <= nr && tlo == ""; i++) {
      on = (h0 + ru[i] <= 1e-12 * h0)
      if (on && ttd == "") ttd = rt[i]
      else if (!on && ttd != "") tlo = rt[i]
    }
    if (tlo == "") { print "plate-dispersion: the reference probe does not touch down and lift off" > "/dev/stderr"; exit 2 }
    if (mode == "window") { printf "%.6g,%.6g\n", ttd, tlo; exit 0 }
    w = (tlo - ttd) / 2; J = sqrt(2 * g * h0)
    kink(ttd); d1 = delta; s1 = shape
    kink(tlo)
    printf "%.6g,%.6g,%.6g,%.6g,%.6g\n", d1, s1, delta, shape, after
  }' "$ref" "$run"
