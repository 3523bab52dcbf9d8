#!/usr/bin/env bash
# The bouncing-plate comparison (reference paper Figure 2, issue "bouncing
# plate"): every contact method on the same mesh and time step, against a
# fine reference, in one table and one set of overlay plots.
#
#   bash scripts/compare-plate.sh [-lc 0.058] [-dt 2.5e-4] [-T 1] [-out out/compare-plate] [-docs]
#        [-skip-build] [plate args...]
#
# Methods: NBM (paper, consistent mass), NBM with the massless boundary
# (mass redistribution), Moreau-Jean with e = 0, Nitsche theta = 1, 0, -1,
# penalty. Reference: NBM with the massless boundary on lc/4 and dt/4 (the
# methods converge to the same solution; the agreement test checks it for
# Nitsche). Installs what is missing and builds first (both idempotent;
# -skip-build: neither, the plugin of $NBM_BUILD, default ./build, is used).
# Writes, in the -out folder:
#   table.csv, table.md     per method: max penetration, energy drift, contact
#                           intervals per node per impact (chattering),
#                           L2 distances of y_com and u_probe to the reference
#                           over (0,T) and over the first bounce, the dispersion
#                           measure over the first impact (below), wall time per
#                           simulated second (whole FreeFem++ run, mesh included);
#                           a last row, "check", is NBM with the massless boundary
#                           on lc/2, dt/2: its distances to the reference bound
#                           what the reference itself can resolve
#   overlay.png             u_probe, y_com, total energy, contact force, and the
#                           probe's displacement and velocity over the first impact
#   <method>.csv, ...       the runs themselves
# Dispersion measure (scripts/plate-dispersion.sh, the plate's version of the
# kink metrics of edp/compare-bar.edp): the probe's velocity jumps by about
# sqrt(2 g h0) at the touch-down and at the lift-off, the arrival of the front
# reflected at the top face (it crossed the plate twice: dispersion). Around
# each kink t* of the reference, over W = [t* - w, t* + w] with w half the
# reference's contact duration of the probe (about H/c_p):
#   arrival  delta = the shift s minimising S(s) = int_W |v_h(t) - v_ref(t - s)| dt
#            (v: mean velocity of each step; positive: late),
#   shape    S(delta)/sqrt(2 g h0): what remains after the best shift
#            (smeared front, trailing oscillations), and its part after t*,
# in units of w. The first impact: release to one crossing after lift-off. The
# lift-off's part after t* is the front and its trail (dispersion proper); its
# part before t* is the contact node's motion while closed (Nitsche, penalty:
# it oscillates in the contact spring), the touch-down's S the landing.
# -docs also copies table.md and overlay.png to docs/compare-plate.{md,png}
# and the NBM run's snapshots to docs/bouncing-plate-snapshots.png (the
# table and figures of docs/results/plate.md).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
lc=0.058 dt=2.5e-4 T=1 out="$repo/out/compare-plate" docs=0 build=1
h0=0.1 grav=10  # plate-setup.idp's defaults, passed on when given
args="$*"
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    -lc) lc=$2; shift 2 ;;
    -dt) dt=$2; shift 2 ;;
    -T) T=$2; shift 2 ;;
    -out) out=$2; shift 2 ;;
    -docs) docs=1; shift ;;
    -skip-build) build=0; shift ;;
    -h0) h0=$2; extra+=("$1" "$2"); shift 2 ;;
    -grav) grav=$2; extra+=("$1" "$2"); shift 2 ;;
    *) extra+=("$1"); shift ;;
  esac
done
enter_sweep "$build" "$out"
run() {  # run <name> <script> [args...]: runs, times, keeps the summary line
  local name=$1 script=$2
  shift 2
  local t0 t1
  t0=$(date +%s.%N)
  bash "$repo/tests/scripts/run-freefem.sh" "$NBM_BUILD" "$repo" "$repo/edp/$script" -lc "$lc" -dt "$dt" -T "$T" \
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
check_lc=$(awk -v a="$lc" 'BEGIN { print a / 2 }')
check_dt=$(awk -v a="$dt" 'BEGIN { print a / 2 }')
lc=$check_lc dt=$check_dt run check bouncing-plate.edp -mass redistributed

mgh0=$(summary_value "$(cat nbm.log)" mgh0)
# The first bounce: until the first lift-off of the reference plus its fall time.
tw=$(awk -v h0="$h0" -v g="$grav" 'BEGIN { printf "%.4g", 2.5 * sqrt(2 * h0 / g) }')
# The first impact: the reference probe's touch-down and lift-off, w.
IFS=, read -r t_td t_lo < <(bash "$repo/scripts/plate-dispersion.sh" -window reference.csv "$h0")
w=$(awk -v a="$t_td" -v b="$t_lo" 'BEGIN { printf "%.4g", (b - a) / 2 }')
echo "method,label,max_penetration,energy_drift_final,energy_drift_max,contact_intervals_per_node_per_impact_mean,contact_intervals_per_node_per_impact_max,impacts,l2_distance_y_com,l2_distance_u_probe,l2_distance_y_com_first_bounce,l2_distance_u_probe_first_bounce,touchdown_arrival,touchdown_shape,liftoff_arrival,liftoff_shape,liftoff_shape_after,walltime_per_simulated_second" > table.csv
rows=("${methods[@]}" check)
row_labels=("${labels[@]}" "check: NBM massless lc/2 dt/2")
for i in "${!rows[@]}"; do
  m=${rows[$i]}
  row=$(bash "$repo/scripts/plate-metrics.sh" "$m.csv" "$m-contact.csv" reference.csv "$mgh0" "$tw")
  disp=$(bash "$repo/scripts/plate-dispersion.sh" "$m.csv" reference.csv "$h0" "$grav")
  echo "$m,${row_labels[$i]},$row,$disp,$(cat "$m.walltime")" >> table.csv
done

{
  echo "Bouncing plate, P1, lc = $lc (about $(summary_value "$(cat nbm.log)" triangles) triangles), dt = $dt, T = $T."
  echo "Produced by \`bash scripts/compare-plate.sh $args\`; reference: NBM with the massless boundary, lc = $ref_lc, dt = $ref_dt."
  echo "Energy drift relative to m g h0 = $mgh0; chattering: contact intervals per node per impact (1 = no chattering)."
  echo
  echo "L2 distances to the reference over (0, T) and over the first bounce (0, $tw)."
  echo "Dispersion over the first impact (scripts/plate-dispersion.sh): the reference probe touches down at $t_td and lifts off at $t_lo"
  echo "(the front reflected at the top arriving), w = $w; per kink: arrival delta (positive: late) and shape S (after the best shift),"
  echo "in units of w, from the probe velocity over [t* - w, t* + w]; for the lift-off also S's part after t* (the front and its trail)."
  echo "The check row: NBM massless on lc/2 = $check_lc, dt/2 = $check_dt (its distances bound what the reference resolves)."
  echo
  echo "| method | max penetration | energy drift (final) | max energy drift | contact intervals / node / impact (mean, max) | impacts | L2 dist. y_com | L2 dist. u_probe | first bounce: y_com | first bounce: u_probe | touch-down: delta, S | lift-off: delta, S (after t*) | wall time / simulated s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %.3g | %.3g | %.3g | %.2f, %d | %d | %.3g | %.3g | %.3g | %.3g | %.3f, %.3f | %.3f, %.3f (%.3f) | %.3g s |\n", $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17, $18 }' table.csv
} > table.md
cat table.md

# Overlay plots: one curve per run, the reference thick.
curves() {  # curves <column>, or vprobe: the mean velocity of each step, du_probe/dt
  local col=$1
  [ "$col" = vprobe ] && col='(v = ($4 - u0) / ($1 - t0), t0 = $1, u0 = $4, v)'
  local list="'reference.csv' using 1:$col with lines lw 3 lc rgb 'black' title 'reference (NBM massless, lc/4, dt/4)'"
  local colours=(dark-green orange dark-violet web-blue red brown gray40)
  for i in "${!methods[@]}"; do
    list="$list, '${methods[$i]}.csv' using 1:$col with lines lw 1.2 lc rgb '${colours[$i]}' title '${labels[$i]}'"
  done
  echo "$list"
}
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1400,1300 font ',10'
set output 'overlay.png'
set multiplot layout 3,2 title 'Bouncing plate: all methods, lc = $lc, dt = $dt'
set grid; set xlabel 't'; set key top right font ',8' opaque box
set ylabel 'u_{probe}'; plot $(curves 4)
unset key
set ylabel 'y_{com}'; plot $(curves 2)
set ylabel 'total energy'; plot $(curves 11)
set ylabel 'total contact force'; plot $(curves 5)
set xrange [$t_td - $w:$t_lo + $w]
set arrow 1 from $t_td, graph 0 to $t_td, graph 1 nohead dt 2; set arrow 2 from $t_lo, graph 0 to $t_lo, graph 1 nohead dt 2
set ylabel 'u_{probe}, first impact'; plot $(curves 4)
t0 = -1; u0 = 0
set ylabel 'v_{probe} (step means), first impact'; plot $(curves 'vprobe')
unset multiplot
GP
echo "compare-plate: wrote $out/table.md, table.csv, overlay.png"
if [ $docs = 1 ]; then
  cp table.md "$repo/docs/compare-plate.md"
  cp overlay.png "$repo/docs/compare-plate.png"
  cp nbm-snapshots.png "$repo/docs/bouncing-plate-snapshots.png"
  echo "compare-plate: copied the table and the figure to $repo/docs"
fi
