#!/usr/bin/env bash
# The 3D drop at scale (issue 14): edp/drop-3d.edp on one mesh, once with
# contact and once with the obstacle out of reach (-contactFree 1: the same
# mesh, matrices, contact nodes and solver, no contact ever), and the cost
# per step of each side by side.
#
#   bash scripts/drop-3d-scale.sh [-lc 0.04] [-order 2] [-dt 1e-3] [-T 0.6]
#        [-repeat 2] [-out out/drop-3d-scale] [-record] [-skip-build] [drop-3d args...]
#
# Default: the largest mesh whose runs take a few minutes each on a 2-core
# machine (P2, lc = 0.04: 5465 tetrahedra, 26994 dofs, 783 contact nodes).
# Prints, and writes to <out>/results.md: tetrahedra, dofs, contact nodes,
# steps, and per run the setup CPU time (assembly, NBM object, nbmInit), the
# CPU time per nbmStep (clock(), summed over the steps: the step alone; with
# contact, also its mean over the steps that end with closed contacts), the
# wall time per step of the whole time loop (output and checks included;
# time() counts whole seconds) and the wall time of the whole FreeFem++ run
# (mesh generation included); then the ratios contact / contact-free. The
# runs are sequential, -repeat rounds of (contact, contact-free); of each
# kind the round with the smallest CPU per step is reported, and every
# round's figures are listed (their spread says how much other work on the
# machine perturbed them), with the load average before and after.
# -record copies results.md to bench/RESULTS-drop3d.md.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
lc=0.04 order=2 dt=1e-3 T=0.6 out="$repo/out/drop-3d-scale" record=0 build=1 repeat=2
args="$*"
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -lc) lc=$2; shift 2 ;;
    -order) order=$2; shift 2 ;;
    -dt) dt=$2; shift 2 ;;
    -T) T=$2; shift 2 ;;
    -out) out=$2; shift 2 ;;
    -record) record=1; shift ;;
    -repeat) repeat=$2; shift 2 ;;
    -skip-build) build=0; shift ;;
    *) extra+=("$1"); shift ;;
  esac
done
enter_sweep "$build" "$out"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
v() { summary_value "$1" "$2"; }
rounds=""
best=()  # per kind (0: contact, 1: contact-free): the run name with the smallest stepCpu
for r in $(seq 1 "$repeat"); do
  line=""
  for free in 0 1; do
    name=run$free-$r
    t0=$(date +%s.%N)
    bash "$repo/tests/scripts/run-freefem.sh" "$NBM_BUILD" "$repo" "$repo/edp/drop-3d.edp" -lc "$lc" \
      -order "$order" -dt "$dt" -T "$T" -plot 0 -vtkFrames 0 -contactFree $free -out "$name" \
      "${extra[@]}" > "$name.log" 2>&1 || { tail -n 5 "$name.log"; echo "drop-3d-scale: $name failed"; exit 1; }
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f\n", b - a }' > "$name.wall"
    sum=$(grep '^drop-3d:' "$name.log" | tail -n 1)
    echo "$sum"
    cpu=$(v "$sum" stepCpu)
    if [ -z "${best[$free]:-}" ] || awk -v a="$cpu" -v b="$(v "$(grep '^drop-3d:' "${best[$free]}.log" | tail -n 1)" stepCpu)" 'BEGIN { exit !(a < b) }'; then
      best[$free]=$name
    fi
    line="$line$(awk -v c="$cpu" 'BEGIN { printf "%.3g ms", 1000 * c }')$([ $free = 0 ] && echo " / " || true)"
  done
  rounds="$rounds${rounds:+; }round $r: $line"
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
s0=$(grep '^drop-3d:' "${best[0]}.log" | tail -n 1) s1=$(grep '^drop-3d:' "${best[1]}.log" | tail -n 1)
{
  echo "# The 3D drop at scale: the step with contact against the contact-free step"
  echo
  echo "3D drop at scale: edp/drop-3d.edp, P$order, lc = $lc: $(v "$s0" tetrahedra) tetrahedra, $(v "$s0" dofs) dofs,"
  echo "$(v "$s0" contactNodes) contact nodes, dt = $dt, $(v "$s0" steps) steps, $(nproc) cores; with contact,"
  awk -F, 'NR > 1 && $NF > 0 { n++; s += $NF; if ($NF > m) m = $NF }
    END { printf "%d steps end with closed contacts (on average %.0f nodes, at most %d).\n", n, n ? s / n : 0, m }' "${best[0]}.csv"
  echo "Produced by \`bash scripts/drop-3d-scale.sh $args\` on $(date -u '+%Y-%m-%d %H:%M UTC'); load average"
  echo "before/after (1, 5, 15 min): $load_before / $load_after (other jobs share the machine: compare the two runs, not absolute figures)."
  echo "CPU per nbmStep, with contact / contact-free, in each round: $rounds; the table: the round of each kind with the smallest."
  echo
  echo "| run | setup CPU | CPU per nbmStep | CPU per nbmStep ending with closed contacts | wall per step (time loop) | wall, whole run |"
  echo "|---|---|---|---|---|---|"
  for free in 0 1; do
    s=$([ $free = 0 ] && echo "$s0" || echo "$s1")
    label=$([ $free = 0 ] && echo "with contact (incline)" || echo "contact-free (obstacle out of reach)")
    awk -v l="$label" -v a="$(v "$s" setupCpu)" -v b="$(v "$s" stepCpu)" -v e="$(v "$s" stepCpuClosed)" \
      -v k="$(v "$s" closedSteps)" -v c="$(v "$s" loopWall)" -v d="$(cat "${best[$free]}.wall")" \
      'BEGIN { printf "| %s | %.3g s | %.3g ms | %s | %.3g ms | %s s |\n", l, a, 1000 * b,
               (k > 0 ? sprintf("%.3g ms (%d steps)", 1000 * e, k) : "-"), 1000 * c, d }'
  done
  awk -v a="$(v "$s0" stepCpu)" -v b="$(v "$s1" stepCpu)" -v e="$(v "$s0" stepCpuClosed)" \
    -v c="$(v "$s0" loopWall)" -v d="$(v "$s1" loopWall)" \
    'BEGIN { printf "| ratio to the contact-free step | | %.3g | %.3g | %s | |\n", a / b, e / b, (d > 0 ? sprintf("%.3g", c / d) : "-") }'
} > results.md
cat results.md
if [ $record = 1 ]; then
  cp results.md "$repo/bench/RESULTS-drop3d.md"
  echo "drop-3d-scale: copied the results to $repo/bench/RESULTS-drop3d.md"
fi
