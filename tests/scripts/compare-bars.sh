#!/usr/bin/env bash
# Smoke run of scripts/compare-bars.sh (issue 16, item 3) on coarse meshes,
# every method, both bars, P1, N = 20, 40, 80, with the assertions that must
# hold for every method (no expected values produced by the code itself):
#   - convergence towards the exact solution: the relative errors of u(0,t)
#     (L2(0,T)) and of u (L2(0,T;L2)) at N = 80 are below those at N = 20;
#   - the NBM schemes (both mass treatments) never penetrate (penetration = 0
#     exactly: closed contacts sit on the obstacle) and, for N >= 40, touch
#     down once per impact (one contact interval per window). At N = 20 they
#     do not: in the bouncing bar's fourth impact the contact end of the
#     coarse bar lifts off at t = 9.517, flies 4 steps (up to 0.03, 0.7% of
#     h0) and lands again at 9.583 before leaving for good (NBM, P1).
#   - Moreau-Jean with e = 1 conserves the energy (Newton's law with e = 1 is
#     energy-preserving and the theta = 1/2 scheme conserves it in flight):
#     max drift <= 1e-8 of the exact energy;
#   - rates where the literature fixes them: on the clamped bar (the benchmark
#     of Chouly, Hild & Renard 2015) the fitted rate of the relative
#     L2(0,T;L2) error of u is >= 0.5 for every method. Why 0.5: the solution
#     has kinks (u in H^{3/2-eps}), for which the a priori estimates of
#     Nitsche's and penalty methods (CHR15, part 1) and of mass-redistribution
#     schemes (Doyen, Ern & Piperno 2011) give h^{1/2} in the energy norm, and
#     the energy norm bounds the L2 norm of u. On the bouncing bar no rate is
#     asserted: on N = 20..80 Nitsche theta = 1, 0 are not yet asymptotic
#     (fitted 0.25), the full sweep (scripts/compare-bars.sh) reports the rates.
#   compare-bars.sh <build> <repo>
set -eu
build=$1 repo=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
NBM_BUILD=$build bash "$repo/scripts/compare-bars.sh" -skip-build -orders "1" -Ns "20 40 80" \
  -out "$work" > "$work/out.txt" 2>&1 || { tail -n 30 "$work/out.txt"; echo "FAIL: compare-bars.sh"; exit 1; }
grep -A 12 'Fitted rates' "$work/tables.md" || true
awk -F, '
  NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  {
    id = $1 " " $2 " P" $3; N = $4
    eu0 = $col["errU0"]; eu = $col["errU"]
    if (!(id in nmin) || N < nmin[id]) { nmin[id] = N; u0min[id] = eu0; umin[id] = eu }
    if (!(id in nmax) || N > nmax[id]) { nmax[id] = N; u0max[id] = eu0; umax[id] = eu }
    x = log(N); y = log(eu); sx[id] += x; sy[id] += y; sxx[id] += x * x; sxy[id] += x * y; n[id]++
    if ($2 == "nbm" || $2 == "nbm-massless") {
      if ($col["penetration"] != 0) { print "FAIL: " id " N=" N " penetrates: " $col["penetration"]; bad = 1 }
      if (N >= 40 && $col["intervalsMax"] != 1) { print "FAIL: " id " N=" N " chatters: " $col["intervalsMax"] " contact intervals"; bad = 1 }
    }
    # The massless boundary on the bouncing bar at N = 80 against the exact
    # solution: no more than 2% above the errors with the trapezoidal contact forces
    # (0.0492, 0.0558: docs/compare-bars.md); energy = "monotone" gives
    # 0.0549, 0.0614 (docs/energy.md).
    if (id == "bouncing nbm-massless P1" && N == 80 && !(eu0 <= 0.0502 && eu <= 0.0570)) {
      print "FAIL: " id " N=80 errors of u(0,t), u " eu0 ", " eu " > 0.0502, 0.0570"; bad = 1
    }
    if ($2 == "mj1" && !($col["energyDriftMax"] <= 1e-8)) { print "FAIL: " id " N=" N " energy drift " $col["energyDriftMax"]; bad = 1 }
  }
  END {
    for (id in n) {
      rate = -(n[id] * sxy[id] - sx[id] * sy[id]) / (n[id] * sxx[id] - sx[id] * sx[id])
      printf "%-28s errU0 %.4g -> %.4g, errU %.4g -> %.4g (N = %d -> %d), fitted rate of errU %.2f\n", id, u0min[id], u0max[id], umin[id], umax[id], nmin[id], nmax[id], rate
      if (!(u0max[id] < u0min[id])) { print "FAIL: " id ": error of u(0,t) did not decrease"; bad = 1 }
      if (!(umax[id] < umin[id])) { print "FAIL: " id ": error of u did not decrease"; bad = 1 }
      if (id ~ /^clamped/ && !(rate >= 0.5)) { print "FAIL: " id ": fitted rate of errU " rate " < 0.5"; bad = 1 }
    }
    exit bad ? 1 : 0
  }' "$work/runs.csv"
echo "compare-bars smoke: all assertions hold"
