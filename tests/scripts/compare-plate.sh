#!/usr/bin/env bash
# Smoke run of scripts/compare-plate.sh (issue 16, item 4) on a coarse mesh
# (lc = 0.116, dt = 5e-4, T = 0.2: the first impact; reference lc/4, dt/4),
# every method, with the assertions on its dispersion measure that must hold
# (no expected values produced by the code itself):
#   - every method's five dispersion numbers are finite;
#   - the landing is exact for the schemes without a contact spring (NBM,
#     both masses, and Moreau-Jean): the probe falls freely (Newmark and the
#     theta = 1/2 scheme integrate constant gravity exactly) and is at rest
#     once on the ground, so only the run's and the reference's landing steps
#     can differ, each by at most the impact speed J times its step: the
#     touch-down shape is <= (dt + dt_ref)/w;
#   - refinement: NBM with the massless boundary on lc/2, dt/2 (the "check"
#     row) has a smaller lift-off shape (after t*, the front and its trail)
#     than on lc, dt.
#   compare-plate.sh <build> <repo>
set -eu
build=$1 repo=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lc=0.116 dt=5e-4
NBM_BUILD=$build bash "$repo/scripts/compare-plate.sh" -skip-build -lc $lc -dt $dt -T 0.2 \
  -out "$work" > "$work/out.txt" 2>&1 || { tail -n 30 "$work/out.txt"; echo "FAIL: compare-plate.sh"; exit 1; }
grep '^|' "$work/table.md" | cut -d'|' -f2,12,13
IFS=, read -r t_td t_lo < <(bash "$repo/scripts/plate-dispersion.sh" -window "$work/reference.csv" 0.1)
awk -F, -v dt=$dt -v t_td="$t_td" -v t_lo="$t_lo" '
  NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  {
    m = $1
    for (k = col["touchdown_arrival"]; k <= col["liftoff_shape_after"]; k++)
      if ($k !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) { print "FAIL: " m ": dispersion value not finite: " $k; bad = 1 }
    bound = (dt + dt / 4) / ((t_lo - t_td) / 2)
    if ((m == "nbm" || m == "nbm-massless" || m == "moreau-jean" || m == "check") && !($col["touchdown_shape"] <= bound)) {
      print "FAIL: " m ": touch-down shape " $col["touchdown_shape"] " > " bound; bad = 1
    }
    after[m] = $col["liftoff_shape_after"]
  }
  END {
    printf "lift-off shape after t*, NBM massless: lc %.4g, lc/2 %.4g\n", after["nbm-massless"], after["check"]
    if (!(after["check"] < after["nbm-massless"])) { print "FAIL: no decrease under refinement"; bad = 1 }
    exit bad ? 1 : 0
  }' "$work/table.csv"
echo "compare-plate smoke: all assertions hold"
