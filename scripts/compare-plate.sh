#!/usr/bin/env bash
# The bouncing-plate comparison (reference paper Figure 2, issue "bouncing
# plate"): every contact method on the same mesh and time step, against a
# fine reference, in one table and one set of overlay plots.
#
#   bash scripts/compare-plate.sh [-lc 0.058] [-dt 2.5e-4] [-T 1] [-out out/compare-plate] [-docs] [plate args...]
#
# Methods: NBM (paper, consistent mass), NBM with the massless boundary
# (mass redistribution), Moreau-Jean with e = 0, Nitsche theta = 1, 0, -1,
# penalty. Reference: NBM with the massless boundary on lc/4 and dt/4 (the
# methods converge to the same solution; the agreement test checks it for
# Nitsche). Installs what is missing and builds first (both idempotent).
# Writes, in the -out folder:
#   table.csv, table.md     per method: max penetration, energy drift, contact
#                           intervals per node per impact (chattering),
#                           L2 distances of y_com and u_probe to the reference
#                           over (0,T) and over the first bounce, wall time per
#                           simulated second (whole FreeFem++ run, mesh included)
#   overlay.png             u_probe, y_com, total energy, contact force
#   <method>.csv, ...       the runs themselves
# -docs also copies table.md and overlay.png to docs/compare-plate.{md,png}
# and the NBM run's snapshots to docs/bouncing-plate-snapshots.png (the
# README's table and figures).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
lc=0.058 dt=2.5e-4 T=1 out="$repo/out/compare-plate" docs=0
args="$*"
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -lc) lc=$2; shift 2 ;;
    -dt) dt=$2; shift 2 ;;
    -T) T=$2; shift 2 ;;
    -out) out=$2; shift 2 ;;
    -docs) docs=1; shift ;;
    *) extra+=("$1"); shift ;;
  esac
done
bash "$repo/scripts/install-deps.sh" >/dev/null
bash "$repo/scripts/build.sh" >/dev/null
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$out"
run() {  # run <name> <script> [args...]: runs, times, keeps the summary line
  local name=$1 script=$2
  shift 2
  local t0 t1
  t0=$(date +%s.%N)
  bash "$repo/scripts/freefem.sh" "$repo/edp/$script" -lc "$lc" -dt "$dt" -T "$T" \
    -vtkFrames 0 -snapshots 0 -out "$name" "${extra[@]}" "$@" > "$name.log" 2>&1 ||
    { tail -n 5 "$name.log"; echo "compare-plate: $name failed"; exit 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" -v T="$T" 'BEGIN { printf "%.4g\n", (b - a) / T }' > "$name.walltime"
  grep '^bouncing-plate:' "$name.log" | tail -n 1
}

methods=(nbm nbm-massless moreau-jean nitsche-theta1 nitsche-theta0 nitsche-theta-1 penalty)
labels=("NBM (paper)" "NBM massless boundary" "Moreau-Jean e = 0" "Nitsche theta = 1"
        "Nitsche theta = 0" "Nitsche theta = -1" "penalty")  # no commas: CSV fields
run nbm bouncing-plate.edp -snapshots 6
run nbm-massless bouncing-plate.edp -mass redistributed
run moreau-jean bouncing-plate.edp -scheme moreau-jean -restitution 0
run nitsche-theta1 bouncing-plate-nitsche.edp -theta 1
run nitsche-theta0 bouncing-plate-nitsche.edp -theta 0
run nitsche-theta-1 bouncing-plate-nitsche.edp -theta -1
run penalty bouncing-plate-penalty.edp
ref_lc=$(awk -v a="$lc" 'BEGIN { print a / 4 }')
ref_dt=$(awk -v a="$dt" 'BEGIN { print a / 4 }')
lc=$ref_lc dt=$ref_dt run reference bouncing-plate.edp -mass redistributed

mgh0=$(summary_value "$(cat nbm.log)" mgh0)
# The first bounce: until the first lift-off of the reference plus its fall time.
tw=$(awk -v h0=0.1 -v g=10 'BEGIN { printf "%.4g", 2.5 * sqrt(2 * h0 / g) }')
echo "method,label,max_penetration,energy_drift_final,energy_drift_max,contact_intervals_per_node_per_impact_mean,contact_intervals_per_node_per_impact_max,impacts,l2_distance_y_com,l2_distance_u_probe,l2_distance_y_com_first_bounce,l2_distance_u_probe_first_bounce,walltime_per_simulated_second" > table.csv
for i in "${!methods[@]}"; do
  m=${methods[$i]}
  row=$(bash "$repo/scripts/plate-metrics.sh" "$m.csv" "$m-contact.csv" reference.csv "$mgh0" "$tw")
  echo "$m,${labels[$i]},$row,$(cat "$m.walltime")" >> table.csv
done

{
  echo "Bouncing plate, P1, lc = $lc (about $(summary_value "$(cat nbm.log)" triangles) triangles), dt = $dt, T = $T."
  echo "Produced by \`bash scripts/compare-plate.sh $args\`; reference: NBM with the massless boundary, lc = $ref_lc, dt = $ref_dt."
  echo "Energy drift relative to m g h0 = $mgh0; chattering: contact intervals per node per impact (1 = no chattering)."
  echo
  echo "L2 distances to the reference over (0, T) and over the first bounce (0, $tw)."
  echo
  echo "| method | max penetration | energy drift (final) | max energy drift | contact intervals / node / impact (mean, max) | impacts | L2 dist. y_com | L2 dist. u_probe | first bounce: y_com | first bounce: u_probe | wall time / simulated s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %.3g | %.3g | %.3g | %.2f, %d | %d | %.3g | %.3g | %.3g | %.3g | %.3g s |\n", $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13 }' table.csv
} > table.md
cat table.md

# Overlay plots: one curve per run, the reference thick.
curves() {  # curves <column>
  local col=$1
  local list="'reference.csv' using 1:$col with lines lw 3 lc rgb 'black' title 'reference (NBM massless, lc/4, dt/4)'"
  local colours=(dark-green orange dark-violet web-blue red brown gray40)
  for i in "${!methods[@]}"; do
    list="$list, '${methods[$i]}.csv' using 1:$col with lines lw 1.2 lc rgb '${colours[$i]}' title '${labels[$i]}'"
  done
  echo "$list"
}
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1400,900 font ',10'
set output 'overlay.png'
set multiplot layout 2,2 title 'Bouncing plate: all methods, lc = $lc, dt = $dt'
set grid; set xlabel 't'; set key top right font ',8' opaque box
set ylabel 'u_{probe}'; plot $(curves 4)
unset key
set ylabel 'y_{com}'; plot $(curves 2)
set ylabel 'total energy'; plot $(curves 11)
set ylabel 'total contact force'; plot $(curves 5)
unset multiplot
GP
echo "compare-plate: wrote $out/table.md, table.csv, overlay.png"
if [ $docs = 1 ]; then
  cp table.md "$repo/docs/compare-plate.md"
  cp overlay.png "$repo/docs/compare-plate.png"
  cp nbm-snapshots.png "$repo/docs/bouncing-plate-snapshots.png"
  echo "compare-plate: copied the table and the figure to $repo/docs"
fi
