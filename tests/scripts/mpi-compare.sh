#!/usr/bin/env bash
# One example run three ways: CHOLMOD in one process, MUMPS in one process,
# and MUMPS over 2 MPI ranks (mpirun -np 2 FreeFem++-mpi, the plugin's
# solver = "mumps"; method.md §4). Every rank of the parallel run holds the
# whole state and writes its own <out>.csv (rank r > 0: <out>-rank<r>.csv,
# edp/nbm-mpi.idp). Passes when
#   - the two ranks wrote the same CSV, bit for bit (both hold the host's
#     broadcast results);
#   - the 2-rank run agrees with the 1-process MUMPS run (their factorizations
#     differ in the order of operations), and MUMPS with CHOLMOD: in every CSV
#     column the largest |difference| is at most <tol> times the column's
#     largest magnitude (the CSVs hold 12 significant digits). Columns whose
#     magnitude stays below 1e-9 of the largest column's are round-off
#     measures themselves (a residual, an error against the exact solution):
#     they are not compared.
# Prints the measured differences.
#   mpi-compare.sh <build> <repo> <script.edp> <out> <tol> [script args...]
set -u
build=$1 repo=$2 script=$3 out=$4 tol=$5
shift 5
run=$repo/tests/scripts/run-freefem.sh mpirun=$repo/tests/scripts/run-freefem-mpi.sh

bash "$run" "$build" "$repo" "$script" "$@" -solver cholmod -out "$out-cholmod" > "$out-cholmod.log" 2>&1 \
  || { cat "$out-cholmod.log"; echo "mpi-compare: the CHOLMOD run failed"; exit 1; }
bash "$run" "$build" "$repo" "$script" "$@" -solver mumps -out "$out-mumps" > "$out-mumps.log" 2>&1 \
  || { cat "$out-mumps.log"; echo "mpi-compare: the 1-process MUMPS run failed"; exit 1; }

bash "$mpirun" "$build" "$repo" 2 "$script" "$@" -solver mumps -out "$out-mpi" > "$out-mpi.log" 2>&1 \
  || { cat "$out-mpi.log"; echo "mpi-compare: the 2-rank MUMPS run failed"; exit 1; }

/usr/bin/python3 - "$out" "$tol" <<'EOF'
import csv, sys
out, tol = sys.argv[1], float(sys.argv[2])
def read(name):
    rows = list(csv.reader(open(name)))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
head, cholmod = read(out + "-cholmod.csv")
_, mumps = read(out + "-mumps.csv")
_, rank0 = read(out + "-mpi.csv")
_, rank1 = read(out + "-mpi-rank1.csv")
if not (len(cholmod) == len(mumps) == len(rank0) == len(rank1)) or len(cholmod) < 2:
    sys.exit(f"mpi-compare: runs of different lengths {len(cholmod)}, {len(mumps)}, {len(rank0)}, {len(rank1)}")
scales = [max(abs(r[j]) for r in cholmod) for j in range(len(head))]
compared = [j for j in range(len(head)) if scales[j] > 1e-9 * max(scales)]
def relative(a, b):  # the largest column-relative |a - b| and its column
    worst, column = 0.0, head[0]
    for j in compared:
        d = max(abs(r[j] - s[j]) for r, s in zip(a, b)) / scales[j]
        if d > worst:
            worst, column = d, head[j]
    return worst, column
ranks_equal = rank0 == rank1
parallel, pcol = relative(rank0, mumps)
libraries, lcol = relative(mumps, cholmod)
skipped = [head[j] for j in range(len(head)) if j not in compared]
print(f"mpi-compare: {len(cholmod)} rows x {len(head)} columns "
      f"({'round-off columns not compared: ' + ', '.join(skipped) if skipped else 'all compared'}); ranks 0 and 1 "
      f"{'identical' if ranks_equal else 'DIFFER'}; 2 ranks against 1 process (MUMPS): "
      f"{parallel:.3g} ({pcol}); MUMPS against CHOLMOD: {libraries:.3g} ({lcol}); relative, "
      f"bound {tol:g}")
sys.exit(0 if ranks_equal and parallel <= tol and libraries <= tol
         else "mpi-compare: a difference exceeds its bound")
EOF
