#!/usr/bin/env bash
# A restart file written on 2 MPI ranks (edp/restart.edp, -solver mumps;
# method.md §4). The plate's run is saved after N steps by a 2-rank job (both
# ranks must write the same file, bit for bit), then resumed for N steps
#   (a) by one process, against 2N uninterrupted steps in one process;
#   (b) by a 2-rank job, against 2N uninterrupted steps on 2 ranks.
# The time and the active set must be equal, U, V and the acceleration agree
# to <tol> of each field's largest magnitude. Not bit for bit: MUMPS's
# factorization on several ranks adds the contributions of the ranks in the
# order their messages arrive, so two identical 2-rank runs already differ by
# round-off (measured 1e-12 to 1e-10 of the fields after 1200 steps); in one
# process MUMPS, like CHOLMOD, restarts bit for bit (tests/scripts/restart.sh,
# script.restart-mumps*). Prints the measured differences.
#   mpi-restart.sh <build> <repo> <tol> [restart.edp args...]
set -u
build=$1 repo=$2 tol=$3
shift 3
tag=$(printf '%s' "mpi-restart$*" | tr -c 'A-Za-z0-9.-' '_')
script=$repo/edp/restart.edp
n=600  # t = 0.15 at restart.edp's dt: during the first impact
one() { bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$script" -solver mumps -vtkFrames 0 -out "$tag" "$@"; }
two() { bash "$repo/tests/scripts/run-freefem-mpi.sh" "$build" "$repo" 2 "$script" -solver mumps -vtkFrames 0 -out "$tag" "$@"; }
step() {  # step <name> <command...>: runs it, shows its last line, stops on failure
  local name=$1 log
  shift
  log=$("$@" 2>&1) || { printf '%s\n' "$log" | tail -n 30; echo "FAIL: $name failed"; exit 1; }
  printf '%s: %s\n' "$name" "$(printf '%s\n' "$log" | grep '^restart:' | tail -n 1)"
}
step "2 ranks, N steps" two "$@" -steps $n -save "$tag-half.txt"
cmp -s "$tag-half.txt" "$tag-half.txt-rank1" \
  || { echo "FAIL: ranks 0 and 1 saved different states"; exit 1; }
step "1 process resumes" one "$@" -steps $n -load "$tag-half.txt" -save "$tag-resumed.txt"
step "1 process, 2N steps" one "$@" -steps $((2 * n)) -save "$tag-full.txt"
step "2 ranks resume" two "$@" -steps $n -load "$tag-half.txt" -save "$tag-resumed-2.txt"
step "2 ranks, 2N steps" two "$@" -steps $((2 * n)) -save "$tag-full-2.txt"

/usr/bin/python3 - "$tag" "$tol" <<'PY'
import sys
tag, tol = sys.argv[1], float(sys.argv[2])
def read(name):  # nbmSaveState (edp/nbm.idp): t, U, V, acceleration, active set, scheme state
    tok = open(name).read().split()
    t, i, arrays = float(tok[0]), 1, []
    for _ in range(4):
        n = int(tok[i]); arrays.append([float(x) for x in tok[i + 1:i + 1 + n]]); i += 1 + n
    return t, arrays
ok = True
for label, resumed, full in (("1 process", "-resumed.txt", "-full.txt"), ("2 ranks", "-resumed-2.txt", "-full-2.txt")):
    (t1, a1), (t2, a2) = read(tag + resumed), read(tag + full)
    worst = []
    for name, x, y in zip(("U", "V", "acceleration"), a1, a2):
        worst.append((max(abs(u - v) for u, v in zip(x, y)) / max(abs(v) for v in y), name))
    d, name = max(worst)
    same = t1 == t2 and a1[3] == a2[3]
    print(f"{label}: resumed against uninterrupted: time and active set ({int(sum(a2[3]))} closed) "
          f"{'equal' if same else 'DIFFER'}; largest difference {d:.3g} of max |{name}| (bound {tol:g})")
    ok = ok and same and d <= tol
sys.exit(0 if ok else "FAIL: a resumed state is not the uninterrupted one")
PY
