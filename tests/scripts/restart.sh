#!/usr/bin/env bash
# Exact restart (edp/restart.edp): a run saved after N steps and resumed must
# reproduce the uninterrupted run bit for bit, (1) in one FreeFem++ process,
# compared at every step after the restart (U, V, acceleration, active set,
# time, energies), and (2) across processes: N steps saved to a file, N more
# from that file in a new process, against 2N uninterrupted steps; the saved
# final states (17 significant digits) must be identical files.
#   restart.sh <build> <repo> [restart.edp args...]
set -eu
build=$1 repo=$2
shift 2
tag=$(printf '%s' "restart$*" | tr -c 'A-Za-z0-9.-' '_')
run() { bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/edp/restart.edp" \
          -vtkFrames 0 -out "$tag" "$@"; }
run "$@" | tail -n 1
n=600  # t = 0.15 at the default dt: during the first impact
run "$@" -steps $n -save "$tag-half.txt" | tail -n 1
run "$@" -steps $n -load "$tag-half.txt" -save "$tag-resumed.txt" | tail -n 1
run "$@" -steps $((2 * n)) -save "$tag-full.txt" | tail -n 1
if cmp -s "$tag-resumed.txt" "$tag-full.txt"; then
  echo "restart across processes: resumed state after $n + $n steps identical to the uninterrupted one"
else
  echo "FAIL: the state resumed from a file differs from the uninterrupted run"
  exit 1
fi
