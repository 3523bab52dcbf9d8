#!/usr/bin/env bash
# Agreement of two contact methods on the bouncing plate under mesh refinement:
# the NBM (edp/bouncing-plate.edp) and a peer (default Nitsche, theta = 1,
# edp/bouncing-plate-nitsche.edp) run on the same problem, the same dt and T,
# at every mesh size of <lc list> (coarse to fine). For each level the
# L2-in-time distances between the two CSVs' y_com and u_probe columns,
#   d = sqrt(sum_n dt (a_n - b_n)^2)   (rows n = 0..steps, identical time grids),
# are printed with the ratios to the previous level; the test fails unless both
# distances decrease at every refinement.
#   plate-agreement.sh <build> <repo> "<lc list>" [args of both scripts...]
# Environment: PEER (default bouncing-plate-nitsche.edp), PEER_ARGS (extra
# arguments of the peer only, default "-theta 1" when unset).
# The decision is made by check_decreasing below; when it passes, the script
# also runs it on the rows in reverse order and requires it to fail there (the
# check can fail). With the levels in reverse order (fine to coarse) the test
# fails, e.g. "0.05 0.1" -dt 1e-4 -T 0.35.
set -eu
build=$1 repo=$2 levels=$3
. "$repo/scripts/lib.sh"
shift 3
peer=${PEER:-bouncing-plate-nitsche.edp}
peerArgs=${PEER_ARGS--theta 1}
run="bash $repo/tests/scripts/run-freefem.sh $build $repo"

# check_decreasing <table>: rows "lc triangles d_ycom d_uprobe"; exit 0 iff both
# distance columns decrease strictly from each row to the next.
check_decreasing() {
  awk 'NR > 1 && !($3 < y && $4 < u) { bad = 1 } { y = $3; u = $4 } END { exit bad }' "$1"
}

# summary <script> [args]: runs it, prints its summary line; stops the test if
# the run fails or prints none.
summary() {
  local out
  if ! out=$($run "$@" 2>&1); then
    printf '%s\n' "$out" | tail -n 15 >&2
    echo "FAIL: $(basename "$1") ${*:2} exited non-zero" >&2; exit 1
  fi
  printf '%s\n' "$out" | grep '^bouncing-plate:' || { echo "FAIL: no summary line from $1" >&2; exit 1; }
}

table=$(mktemp)
trap 'rm -f "$table" "$table.rev"' EXIT
tag=agreement-$(printf '%s' "$peer$peerArgs$*" | tr -c 'A-Za-z0-9.-' '_')
for lc in $levels; do
  start=$SECONDS
  nbmLine=$(summary "$repo/edp/bouncing-plate.edp" -lc "$lc" -vtkFrames 0 -snapshots 0 \
    -out "$tag-nbm-$lc" "$@")
  # shellcheck disable=SC2086
  peerLine=$(summary "$repo/edp/$peer" -lc "$lc" -vtkFrames 0 -snapshots 0 \
    -out "$tag-peer-$lc" "$@" $peerArgs)
  echo "$nbmLine"
  echo "$peerLine"
  echo "  (lc = $lc: $((SECONDS - start)) s)"
  triangles=$(summary_value "$peerLine" triangles)
  awk -F, -v lc="$lc" -v nt="$triangles" '
    FNR == 1 { next }
    NR == FNR { t[FNR] = $1; y[FNR] = $2; u[FNR] = $4; na = FNR; next }
    {
      nb = FNR
      if (!(FNR in t) || (t[FNR] - $1 > 1e-9 || $1 - t[FNR] > 1e-9)) {
        print "FAIL: time grids differ at row " FNR > "/dev/stderr"; exit 2
      }
      if (FNR > 2) dt = $1 - tp; tp = $1
      if (FNR > 2) { dy += dt * (y[FNR] - $2)^2; du += dt * (u[FNR] - $4)^2 }
    }
    END {
      if (na != nb || na < 3) { print "FAIL: row counts " na ", " nb > "/dev/stderr"; exit 2 }
      printf "%s %s %.6e %.6e\n", lc, nt, sqrt(dy), sqrt(du)
    }' "$tag-nbm-$lc.csv" "$tag-peer-$lc.csv" >> "$table"
done

echo "NBM vs ${peer%.edp} $peerArgs $*: L2(0,T) distances"
printf '%-8s %-10s %-14s %-8s %-14s %-8s\n' lc triangles y_com ratio u_probe ratio
awk '{ ry = NR > 1 ? sprintf("%.3f", $3 / y) : "-"; ru = NR > 1 ? sprintf("%.3f", $4 / u) : "-"
       printf "%-8s %-10s %-14s %-8s %-14s %-8s\n", $1, $2, $3, ry, $4, ru; y = $3; u = $4 }' "$table"

if ! check_decreasing "$table"; then
  echo "FAIL: the distances do not decrease at every refinement"; exit 1
fi
# The check passed: on the same rows in reverse order (increasing distances) it must fail.
if [ "$(wc -l < "$table")" -ge 2 ]; then
  tac "$table" > "$table.rev"
  if check_decreasing "$table.rev"; then
    echo "FAIL: the check also accepts the reversed table (it cannot fail)"; exit 1
  fi
fi
echo "OK: both distances decrease at every refinement"
