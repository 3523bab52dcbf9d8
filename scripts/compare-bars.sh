#!/usr/bin/env bash
# Every contact method on the two bars with exact solutions (issue 16, item 3):
# the bouncing bar (benchmarks.md §A) and the clamped bar (§B), each method,
# order and mesh one run of edp/compare-bar.edp, against the exact solution.
#
#   bash scripts/compare-bars.sh [-orders "1 2 4"] [-Ns "40 80 160 320"]
#        [-problems "bouncing clamped"] [-methods "..."] [-jobs 2]
#        [-maxNk 640] [-out out/compare-bars] [-docs] [-docs-name compare-bars]
#        [-skip-build]
#
# Runs with N k > maxNk (more than maxNk node spacings) are skipped: with
# -orders "1 2 4", P4 then stops at N = 160 (-maxNk 1280 adds N = 320).
# A run whose log already holds its summary line is not run again (-rerun:
# run everything), so an interrupted sweep resumes where it stopped.
# Methods: nbm (paper), nbm-massless, mj0, mj1 (Moreau-Jean e = 0, 1),
# nitsche1, nitsche0, nitsche-1, penalty. Same dt = h/(k c) for all.
# Writes, in the -out folder:
#   runs.csv                 one row per run (the summary keys of compare-bar.edp, wall time)
#   tables.md                per problem and order: errors, penetration, energy,
#                            contact intervals, kink metrics; fitted rates
#   convergence.png          errors of u(0,t), u, v and the contact force against N
#   histories.png            u(0,t), v(0,t) of every method against the exact one (coarsest N, P1)
#   <problem>-<method>-P<k>-N<N>.csv / .log   the runs
# -docs copies tables.md and the PNGs to docs/NAME.md, docs/NAME-*.png, NAME from
# -docs-name (default compare-bars). The P4 tables of docs/results/methods-on-bars.md:
#   bash scripts/compare-bars.sh -orders 4 -Ns "40 80 160" -out out/compare-bars-P4 \
#        -docs -docs-name compare-bars-P4
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
orders="1 2" Ns="40 80 160 320" problems="bouncing clamped"
methods="nbm nbm-massless mj0 mj1 nitsche1 nitsche0 nitsche-1 penalty"
jobs=2 out="$repo/out/compare-bars" docs=0 docs_name=compare-bars build=1 maxNk=640 rerun=0
args="$*"
while [ $# -gt 0 ]; do
  case "$1" in
    -orders) orders=$2; shift 2 ;;
    -Ns) Ns=$2; shift 2 ;;
    -problems) problems=$2; shift 2 ;;
    -methods) methods=$2; shift 2 ;;
    -jobs) jobs=$2; shift 2 ;;
    -maxNk) maxNk=$2; shift 2 ;;
    -out) out=$2; shift 2 ;;
    -docs) docs=1; shift ;;
    -docs-name) docs_name=$2; shift 2 ;;
    -skip-build) build=0; shift ;;
    -rerun) rerun=1; shift ;;
    *) echo "compare-bars: unknown option $1"; exit 1 ;;
  esac
done
enter_sweep "$build" "$out"
start=$(date +%s)

# One run: problem method order N -> <name>.log, <name>.csv, <name>.wall
run_one() {
  local p=$1 m=$2 k=$3 n=$4 name="$1-$2-P$3-N$4" t0 t1
  if [ "$rerun" = 0 ] && [ -s "$name.wall" ] && grep -q '^compare-bar:' "$name.log" 2>/dev/null; then return 0; fi
  t0=$(date +%s.%N)
  if ! bash "$repo/tests/scripts/run-freefem.sh" "$NBM_BUILD" "$repo" "$repo/edp/compare-bar.edp" \
      -problem "$p" -method "$m" -order "$k" -N "$n" -out "$name" > "$name.log" 2>&1; then
    echo "compare-bars: $name failed:"; tail -n 5 "$name.log"; return 1
  fi
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3g\n", b - a }' > "$name.wall"
}
export -f run_one
export repo NBM_BUILD rerun
# Largest runs first, so that the parallel jobs finish together.
for p in $problems; do for m in $methods; do for k in $orders; do for n in $Ns; do
  [ $((n * k)) -le "$maxNk" ] && echo "$((n * k)) $p $m $k $n"
done; done; done; done | sort -rn | cut -d' ' -f2- |
  xargs -P "$jobs" -L 1 bash -c 'run_one "$@"' _
wall=$(( $(date +%s) - start ))

keys="dt errU0 errU errV errLambda penetration energyDriftFinal energyDriftMax impacts intervalsMean intervalsMax kinkArrivalWave kinkShapeWave kinkArrivalContact kinkShapeContact newtonIterations"
{
  echo "problem,method,order,N,${keys// /,},wall"
  for p in $problems; do for m in $methods; do for k in $orders; do for n in $Ns; do
    name="$p-$m-P$k-N$n"
    [ $((n * k)) -le "$maxNk" ] || continue
    line=$(grep '^compare-bar:' "$name.log" | tail -n 1)
    row="$p,$m,$k,$n"
    for key in $keys; do row="$row,$(summary_value "$line" "$key")"; done
    echo "$row,$(cat "$name.wall")"
  done; done; done; done
} > runs.csv
runsum=$(awk -F, 'NR > 1 { s += $NF } END { printf "%.0f", s }' runs.csv)

label() {
  case $1 in
    nbm) echo "NBM (paper)" ;; nbm-massless) echo "NBM massless" ;;
    mj0) echo "Moreau-Jean e=0" ;; mj1) echo "Moreau-Jean e=1" ;;
    nitsche1) echo "Nitsche theta=1" ;; nitsche0) echo "Nitsche theta=0" ;;
    nitsche-1) echo "Nitsche theta=-1" ;; penalty) echo "penalty" ;; *) echo "$1" ;;
  esac
}
labels=""
for m in $methods; do labels="$labels$m@$(label "$m");"; done

{
  echo "Every contact method on the bars with exact solutions (benchmarks.md §A, §B), two periods,"
  echo "dt = h/(k c) for all. Produced by \`bash scripts/compare-bars.sh $args\` (the runs' wall times"
  echo "add up to ${runsum} s, $jobs of them in parallel on a 2-core machine shared with other work). Errors are relative: u(0,t) and the contact force in L2(0,T), u and v in"
  echo "L2(0,T;L2) against the nodal interpolant of the exact field. Penetration: max of -u(0,t) over"
  echo "the displacement scale (h0, a). Energy drift: (final, max over the run) |E_h - E|/E. Contact"
  echo "intervals: per window around an exact contact phase (1 = no chattering), mean and max."
  echo "Kinks (edp/compare-bar.edp's header): arrival error |delta| and shape error S of the jumps of"
  echo "v(0,t), in units of L/c, means over the wave-arrival kinks (W) and the touch-down/lift-off"
  echo "kinks (C). Rates: least-squares slopes of -log(error) against log(N) over N = ${Ns} (N k <= $maxNk)."
  awk -F, -v labels="$labels" '
    BEGIN { n = split(labels, a, ";"); for (i = 1; i < n; i++) { split(a[i], b, "@"); lab[b[1]] = b[2] } }
    NR == 1 { next }
    {
      key = $1 " P" $3
      if (!(key in seen)) { seen[key] = 1; order[++nk] = key }
      rows[key] = rows[key] sprintf("| %s | %d | %.3g | %.3g | %.3g | %.3g | %.3g | %.2g, %.2g | %.2f, %d | %.3g | %.3g | %.3g | %.3g | %s |\n",
        lab[$2], $4, $6, $7, $8, $9, $10, $11, $12, $14, $15, $16, $17, $18, $19, $21)
      m = $2; id = key SUBSEP m
      if (!(id in cnt)) { mlist[key] = mlist[key] " " m }
      c = ++cnt[id]; NN[id, c] = $4
      for (j = 6; j <= 9; j++) ee[id, c, j] = $j; ee[id, c, 17] = $17
    }
    function rate(id, j,   c, sx, sy, sxx, sxy, x, y, nn) {
      nn = cnt[id]; sx = sy = sxx = sxy = 0
      if (nn < 2) return "-"
      for (c = 1; c <= nn; c++) { if (ee[id, c, j] <= 0) return "-"; x = log(NN[id, c]); y = log(ee[id, c, j]); sx += x; sy += y; sxx += x * x; sxy += x * y }
      return sprintf("%.2f", -(nn * sxy - sx * sy) / (nn * sxx - sx * sx))
    }
    END {
      for (i = 1; i <= nk; i++) {
        key = order[i]; split(key, kk, " ")
        printf "\n### %s bar, %s\n\n", (kk[1] == "bouncing" ? "Bouncing" : "Clamped"), kk[2]
        print "| method | N | u(0,t) | u | v | contact force | penetration | energy drift (final, max) | contact intervals (mean, max) | kink arrival W | kink shape W | kink arrival C | kink shape C | wall s |"
        print "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        printf "%s", rows[key]
        printf "\nFitted rates, %s bar, %s:\n\n", kk[1], kk[2]
        print "| method | u(0,t) | u | v | contact force | kink shape W |"
        print "|---|---|---|---|---|---|"
        nm = split(mlist[key], ms, " ")
        for (q = 1; q <= nm; q++) { id = key SUBSEP ms[q]
          printf "| %s | %s | %s | %s | %s | %s |\n", lab[ms[q]], rate(id, 6), rate(id, 7), rate(id, 8), rate(id, 9), rate(id, 17) }
      }
    }' runs.csv
} > tables.md
cat tables.md

# Figures: errors against N (log-log), one row per problem, columns u(0,t), u, v, force;
# histories of the coarsest P1 (or first order) runs.
first_order=${orders%% *}
coarse=${Ns%% *}
colours=(black dark-green orange dark-violet web-blue red brown gray40)
plots_conv() {  # plots_conv <problem> <column>
  local p=$1 col=$2 list="" i=0 k
  for m in $methods; do
    for k in $orders; do
      local dash=$(( k == 1 ? 1 : (k == 2 ? 2 : 3) ))
      list="$list${list:+, }'runs.csv' using (strcol(1) eq '$p' && strcol(2) eq '$m' && \$3 == $k ? \$4 : NaN):$col with linespoints dt $dash lw 1.3 pt $((i + 4)) lc rgb '${colours[$i]}' title '$(label "$m") P$k'"
    done
    i=$((i + 1))
  done
  echo "$list"
}
plots_hist() {  # plots_hist <problem> <column exact> <column numerical>
  local p=$1 ce=$2 cn=$3 list="" i=0
  list="'$p-nbm-P$first_order-N$coarse.csv' using 1:$ce with lines lw 3 lc rgb 'gray70' title 'exact'"
  for m in $methods; do
    list="$list, '$p-$m-P$first_order-N$coarse.csv' using 1:$cn with lines lw 1 lc rgb '${colours[$i]}' title '$(label "$m")'"
    i=$((i + 1))
  done
  echo "$list"
}
nprob=$(echo $problems | wc -w)
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1600,$((450 * nprob + 100)) font ',10'
set output 'convergence.png'
set multiplot layout $nprob,4 title 'Relative errors against the exact solutions (dashes: order), dt = h/(k c)'
set logscale xy; set grid; set xlabel 'N (elements)'
$(for p in $problems; do
  echo "set key off"
  echo "set ylabel '$p bar'"
  echo "set title 'u(0,t), L2(0,T)'; plot $(plots_conv "$p" 6)"
  echo "unset ylabel"
  echo "set title 'u, L2(0,T;L2)'; plot $(plots_conv "$p" 7)"
  echo "set title 'v, L2(0,T;L2)'; plot $(plots_conv "$p" 8)"
  [ "$p" = "${problems%% *}" ] && echo "set key outside right top font ',7'"
  echo "set title 'contact force, L2(0,T)'; plot $(plots_conv "$p" 9)"
done)
unset multiplot
GP
gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1600,$((420 * nprob + 80)) font ',10'
set output 'histories.png'
set multiplot layout $nprob,2 title 'Contact end, P$first_order, N = $coarse, every method against the exact solution'
set grid; set xlabel 't'; set key outside right top font ',8'
$(for p in $problems; do
  echo "set title '$p bar: u(0,t)'; plot $(plots_hist "$p" 3 2)"
  echo "set title '$p bar: v(0,t), first contact'; set xrange [$([ "$p" = bouncing ] && echo '0.5:2.5' || echo '0.5:3.5')]; plot $(plots_hist "$p" 5 4)"
  echo "set autoscale x"
done)
unset multiplot
GP
echo "compare-bars: wrote $out/runs.csv, tables.md, convergence.png, histories.png (this invocation ${wall} s, runs ${runsum} s in all)"
if [ $docs = 1 ]; then
  cp tables.md "$repo/docs/$docs_name.md"
  cp convergence.png "$repo/docs/$docs_name-convergence.png"
  cp histories.png "$repo/docs/$docs_name-histories.png"
  echo "compare-bars: copied the tables and figures to $repo/docs"
fi
