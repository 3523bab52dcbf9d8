#!/usr/bin/env bash
# A bad-input test on 2 MPI ranks (mpirun -np 2 FreeFem++-mpi): the job must
# end, not hang (timeout 120 s; NBM_MPI_TIMEOUT=10 for a rank that waits for
# one that stopped), with a non-zero exit, and its output must match every
# pattern given (grep -E; one per rank, or one for the rank that stopped and
# one for the rank that waited). With no pattern the job must succeed.
#   mpi-expect-error.sh <build-dir> <repo-dir> <script.edp> <args> [pattern...]
# (<args>: the script's arguments in one word, separated by commas.)
set -u
build=$1 repo=$2 script=$3 args=$4
shift 4
IFS=, read -r -a script_args <<< "$args"
out=$(NBM_MPI_TIMEOUT=10 NBM_MPIRUN_LIMIT=120 \
  bash "$repo/tests/scripts/run-freefem-mpi.sh" "$build" "$repo" 2 "$script" "${script_args[@]}" 2>&1)
code=$?
printf '%s\n' "$out" | tail -n 20
if [ $code -eq 124 ]; then echo "FAIL: the job hung (timeout)"; exit 1; fi
if [ $# -eq 0 ]; then
  [ $code -eq 0 ] && { echo "OK: the valid case ran"; exit 0; }
  echo "FAIL: the valid case failed (exit $code)"; exit 1
fi
if [ $code -eq 0 ]; then echo "FAIL: the job succeeded, expected an error"; exit 1; fi
for pattern in "$@"; do
  if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
    echo "FAIL: no line matches /$pattern/"; exit 1
  fi
done
echo "OK: exit $code, every pattern found"
