#!/usr/bin/env bash
# Metrics of one bouncing-plate run against a reference run (both CSVs as
# written by plate-setup.idp), printed as one comma-separated line:
#   max_penetration, energy_drift_final, energy_drift_max (relative to mgh0),
#   mean and max contact intervals per node per impact, impacts,
#   L2(0,T) distances of y_com and u_probe to the reference, then the same
#   over (0, t_window) (the first bounce, before trajectories part)
#   plate-metrics.sh <run.csv> <run-contact.csv> <reference.csv> <mgh0> <t_window>
# An impact is a maximal run of steps with some node in contact; within it,
# each node that touched counts its contact intervals (chattering: > 1). The
# reference is interpolated linearly at the run's times.
set -eu
run=$1 contact=$2 ref=$3 mgh0=$4 tw=$5
l2=$(awk -F, -v tw="$tw" '
  FNR == 1 { next }
  FILENAME == ARGV[1] { rt[++nr] = $1; ry[nr] = $2; ru[nr] = $4; next }
  {
    t = $1
    while (j < nr - 1 && rt[j + 1] < t) j++
    if (j < 1) j = 1
    w = (rt[j + 1] > rt[j]) ? (t - rt[j]) / (rt[j + 1] - rt[j]) : 0
    if (w < 0) w = 0; if (w > 1) w = 1
    dy = $2 - (ry[j] + w * (ry[j + 1] - ry[j])); du = $4 - (ru[j] + w * (ru[j + 1] - ru[j]))
    if (FNR > 2) {
      h = t - tp; iy = h * (dy * dy + dyp * dyp) / 2; iu = h * (du * du + dup * dup) / 2
      sy += iy; su += iu
      if (t <= tw) { wy += iy; wu += iu }
    }
    tp = t; dyp = dy; dup = du
  }
  END { printf "%.6g,%.6g,%.6g,%.6g", sqrt(sy), sqrt(su), sqrt(wy), sqrt(wu) }' "$ref" "$run")
energy=$(awk -F, -v m="$mgh0" '
  FNR == 1 { next }
  { if (FNR == 2) e0 = $11; d = ($11 - e0) / m; if (d < 0) d = -d; if (d > dmax) dmax = d
    if ($6 > pen) pen = $6; last = ($11 - e0) / m }
  END { printf "%.6g,%.6g,%.6g", pen, last, dmax }' "$run")
chatter=$(awk -F, '
  NR == 1 { n = NF - 1; next }
  {
    any = 0; for (k = 1; k <= n; k++) if ($(k + 1) == 1) any = 1
    if (any && !inimpact) { inimpact = 1; impacts++; for (k = 1; k <= n; k++) { cnt[k] = 0; prev[k] = 0 } }
    if (inimpact) for (k = 1; k <= n; k++) { c = $(k + 1); if (c == 1 && prev[k] == 0) cnt[k]++; prev[k] = c }
    if (!any && inimpact) { inimpact = 0; close_impact() }
  }
  function close_impact(   k) { for (k = 1; k <= n; k++) if (cnt[k] > 0) { pairs++; sum += cnt[k]; if (cnt[k] > mx) mx = cnt[k] } }
  END { if (inimpact) close_impact(); printf "%.6g,%d,%d", pairs ? sum / pairs : 0, mx, impacts }' "$contact")
echo "$energy,$chatter,$l2"
