#!/usr/bin/env bash
# One run of a peer method on the bouncing plate (edp/bouncing-plate-nitsche.edp,
# edp/bouncing-plate-penalty.edp): the script must exit 0, print its summary
# line and write its outputs (<out>.csv, <out>.png, <out>-snapshots.png,
# <out>.pvd and its frames). These methods penetrate: the maximal penetration
# (summary line and the CSV's penetration_max column) is printed, and only
# checked to be a finite number >= 0, as is every CSV value.
#   plate-peer-run.sh <build> <repo> <script.edp> [script args...]
set -eu
build=$1 repo=$2 script=$3
. "$repo/scripts/lib.sh"
shift 3
tag=peer-$(printf '%s' "$(basename "$script" .edp)$*" | tr -c 'A-Za-z0-9.-' '_')
rm -f "$tag.csv" "$tag.png" "$tag-snapshots.png" "$tag.pvd" "$tag"-*.vtu
start=$SECONDS
if ! out=$(bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$script" -vtkFrames 10 -out "$tag" "$@" 2>&1); then
  printf '%s\n' "$out" | tail -n 15
  echo "FAIL: $(basename "$script") $* exited non-zero"; exit 1
fi
line=$(printf '%s\n' "$out" | grep '^bouncing-plate:' || true)
echo "$line"
echo "($((SECONDS - start)) s)"
[ -n "$line" ] || { echo "FAIL: no summary line"; exit 1; }
for f in "$tag.csv" "$tag.png" "$tag-snapshots.png" "$tag.pvd" "$tag-0.vtu"; do
  [ -s "$f" ] || { echo "FAIL: $f missing or empty"; exit 1; }
done
pen=$(summary_value "$line" maxPenetration)
newton=$(summary_value "$line" newtonIterations)
awk -F, -v pen="$pen" -v newton="$newton" '
  function finite(s) { return s ~ /^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$/ }
  NR == 1 { next }
  {
    for (i = 1; i <= NF; i++) if (!finite($i)) { print "FAIL: row " NR " column " i ": " $i; bad = 1; exit }
    if ($6 < 0) { print "FAIL: negative penetration_max at t = " $1; bad = 1; exit }
    if ($6 > m) { m = $6; tm = $1 }
    rows++
  }
  END {
    if (bad) exit 1
    if (!finite(pen) || pen < 0) { print "FAIL: maxPenetration=" pen " is not a finite number >= 0"; exit 1 }
    if (!finite(newton) || newton < rows - 1) { print "FAIL: newtonIterations=" newton; exit 1 }
    if (m + 0 != pen + 0 && (m - pen > 1e-5 * pen || pen - m > 1e-5 * pen)) {
      print "FAIL: max of penetration_max " m " differs from maxPenetration " pen; exit 1
    }
    printf "penetration: max %g at t = %g (%d rows, finite); Newton iterations %d\n", m, tm, rows, newton
  }' "$tag.csv"
