#!/usr/bin/env bash
# One obstacle described two ways (say a circle, and the script's own signed
# distance of that circle, or a turning circle and the closed form of its
# moving centre): the two runs of <script.edp> must agree. Each run checks
# its own distances at every step; here, in every CSV column, the largest
# |difference| must be at most <tol> times the column's largest magnitude,
# or 1e-3 of the largest column's if that is more (a column much smaller
# than the others, such as an energy drift, is an accuracy measure whose
# own digits are not the runs' agreement; columns below 1e-9 of the largest
# one are round-off measures and are not compared, nor are counts of
# iterations, whose stopping tests sit at round-off). Prints the measured
# difference.
#   obstacle-forms.sh <build> <repo> <script.edp> <out> <tol> "<args A>" "<args B>" [common args...]
set -u
build=$1 repo=$2 script=$3 out=$4 tol=$5 a=$6 b=$7
shift 7
run=$repo/tests/scripts/run-freefem.sh
# shellcheck disable=SC2086 # the two variants' arguments are word lists
bash "$run" "$build" "$repo" "$script" "$@" $a -out "$out-a" > "$out-a.log" 2>&1 \
  || { cat "$out-a.log"; echo "obstacle-forms: the run with $a failed"; exit 1; }
# shellcheck disable=SC2086
bash "$run" "$build" "$repo" "$script" "$@" $b -out "$out-b" > "$out-b.log" 2>&1 \
  || { cat "$out-b.log"; echo "obstacle-forms: the run with $b failed"; exit 1; }
grep -h "^[a-z0-9-]*: " "$out-a.log" "$out-b.log" | tail -n 2
/usr/bin/python3 - "$out" "$tol" "$a" "$b" <<'PY'
import csv, sys
out, tol, a, b = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
def read(name):
    rows = list(csv.reader(open(name)))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
head, ra = read(out + "-a.csv")
_, rb = read(out + "-b.csv")
if len(ra) != len(rb) or len(ra) < 2:
    sys.exit(f"obstacle-forms: runs of different lengths {len(ra)} and {len(rb)}")
scales = [max(abs(r[j]) for r in ra) for j in range(len(head))]
compared = [j for j in range(len(head))
            if scales[j] > 1e-9 * max(scales) and "iterations" not in head[j]]
scales = [max(c, 1e-3 * max(scales)) for c in scales]
worst, column = 0.0, head[0]
for j in compared:
    d = max(abs(r[j] - s[j]) for r, s in zip(ra, rb)) / scales[j]
    if d > worst:
        worst, column = d, head[j]
print(f"obstacle-forms: {len(ra)} rows, {len(compared)} of {len(head)} columns compared; "
      f"'{a}' against '{b}': {worst:.3g} ({column}), relative, bound {tol:g}")
sys.exit(0 if worst <= tol else 1)
PY
