#!/usr/bin/env bash
# Script-level benchmark (issue "Speed and scale", item 2): wall time per
# simulated second of the bouncing plate through FreeFem++, solved by NBM
# (edp/bouncing-plate.edp: the paper's consistent mass, and -mass
# redistributed) and by Nitsche's method (edp/bouncing-plate-nitsche.edp,
# theta = 1), at three mesh sizes with the same dt. Writes
# bench/RESULTS-scripts.md; the runs and their logs go to out/script-timing.
#
#   bash bench/script-timing.sh [-lc "0.058 0.029 0.0145"] [-dt 6.25e-5] [-T 0.2]
#                               [-repeat 3] [-nobuild] [-out out/script-timing]
#
# Defaults: dt = 6.25e-5 is the plate's dt = 2.5e-4 (about h/(6 c_p)) scaled to
# the finest mesh, lc = 0.0145 (the reference of scripts/compare-plate.sh);
# T = 0.2 holds the free fall (the impact is at t = sqrt(2 h0 / g) = 0.141),
# the first contact phase and the lift-off (about t = 0.17). About 6 minutes
# on 2 cores, almost all of it in the Nitsche runs on the finest mesh.
#
# The plate scripts print no setup time, so every configuration is also run
# with T = 0 (mesh generation by gmsh, assembly, NBM construction or the first
# Nitsche factorization, step-0 output, the history plot): the time-loop cost
# is (whole run) - (T = 0 run). Each run is repeated -repeat times (rounds
# interleaved over the configurations) and the minimum is kept. Only one
# FreeFem++ runs at a time. Both methods' loops include the same per-step
# script work (diagnostics, two CSV rows); -vtkFrames 0 -snapshots 0.
# -nobuild skips scripts/install-deps.sh and scripts/build.sh (e.g. while
# someone else builds in ./build); the report then says the plugin was not
# rebuilt. Timings are never asserted (not a ctest test).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
lcs="0.058 0.029 0.0145" dt=6.25e-5 T=0.2 repeat=3 build=1 out="$repo/out/script-timing"
args="$*"
while [ $# -gt 0 ]; do
  case "$1" in
    -lc) lcs=$2; shift 2 ;;
    -dt) dt=$2; shift 2 ;;
    -T) T=$2; shift 2 ;;
    -repeat) repeat=$2; shift 2 ;;
    -nobuild) build=0; shift ;;
    -out) out=$2; shift 2 ;;
    *) echo "script-timing: unknown option $1" >&2; exit 2 ;;
  esac
done
if [ $build = 1 ]; then
  bash "$repo/scripts/install-deps.sh" >/dev/null
  bash "$repo/scripts/build.sh" >/dev/null
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$out"
raw="$out/runs.csv"
echo "round,method,lc,T,seconds,load1" > "$raw"

methods=(nbm nbm-massless nitsche)
labels=("NBM (paper, consistent mass)" "NBM massless boundary (-mass redistributed)" "Nitsche theta = 1")
margs() {  # margs <method>: the script and its options, in the array margs_
  case "$1" in
    nbm) margs_=(bouncing-plate.edp -mass consistent) ;;
    nbm-massless) margs_=(bouncing-plate.edp -mass redistributed) ;;
    nitsche) margs_=(bouncing-plate-nitsche.edp -theta 1) ;;
  esac
}
run() {  # run <round> <method> <lc> <T>: one FreeFem++ run, timed
  local r=$1 m=$2 lc=$3 t=$4 name="$2-$3-T$4" t0 t1 load
  margs "$m"
  load=$(cut -d' ' -f1 /proc/loadavg)
  t0=$(date +%s.%N)
  bash "$repo/scripts/freefem.sh" "$repo/edp/${margs_[0]}" "${margs_[@]:1}" -lc "$lc" -dt "$dt" -T "$t" \
    -vtkFrames 0 -snapshots 0 -out "$name" > "$name.log" 2>&1 ||
    { tail -n 5 "$name.log"; echo "script-timing: $name failed (log: $out/$name.log)"; exit 1; }
  t1=$(date +%s.%N)
  awk -v r="$r" -v m="$m" -v lc="$lc" -v T="$t" -v a="$t0" -v b="$t1" -v l="$load" \
    'BEGIN { printf "%d,%s,%s,%s,%.3f,%s\n", r, m, lc, T, b - a, l }' >> "$raw"
}

sotime() { date -u -r "$repo/build/plugin/nbm.so" '+%Y-%m-%d %H:%M:%S UTC'; }
so_start=$(sotime)
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
start=$(date +%s)
for r in $(seq 1 "$repeat"); do
  for lc in $lcs; do
    for m in "${methods[@]}"; do
      run "$r" "$m" "$lc" 0
      run "$r" "$m" "$lc" "$T"
    done
  done
  echo "script-timing: round $r of $repeat done ($(( $(date +%s) - start )) s)"
done
load_end=$(cut -d' ' -f1-3 /proc/loadavg)

# One row per (method, lc): sizes from the mesh and the summary line, the
# minimum times over the rounds.
table="$out/table.csv"
echo "method,lc,triangles,dofs,contact_nodes,steps,contact_steps,fixed_s,whole_s,loop_s,loop_per_sim_s,ms_per_step,newton_iterations,refactorizations" > "$table"
for lc in $lcs; do
  for m in "${methods[@]}"; do
    name="$m-$lc-T$T"
    line=$(grep '^bouncing-plate:' "$name.log" | tail -n 1)
    nodes=$(awk 'f { print; exit } /^\$Nodes/ { f = 1 }' "$name.msh")
    csteps=$(awk -F, 'NR > 1 && $7 > 0 { c++ } END { print c + 0 }' "$name.csv")
    awk -F, -v m="$m" -v lc="$lc" -v T="$T" -v tri="$(summary_value "$line" triangles)" -v dofs=$((2 * nodes)) \
        -v cn="$(summary_value "$line" contactNodes)" -v steps="$(summary_value "$line" steps)" -v cs="$csteps" \
        -v nit="$(summary_value "$line" newtonIterations)" -v ref="$(summary_value "$line" refactorizations)" '
      NR > 1 && $2 == m && $3 == lc {
        if ($4 + 0 == 0) { if (f == "" || $5 < f) f = $5 } else { if (w == "" || $5 < w) w = $5 }
      }
      END {
        loop = w - f
        printf "%s,%s,%s,%s,%s,%s,%s,%.3f,%.3f,%.3f,%.4g,%.4g,%s,%s\n", m, lc, tri, dofs, cn, steps, cs,
               f, w, loop, loop / T, 1000 * loop / steps, nit, ref
      }' "$raw" >> "$table"
  done
done

report="$repo/bench/RESULTS-scripts.md"
plugin_state="rebuilt by this run (scripts/build.sh)"
[ $build = 1 ] || plugin_state="not rebuilt by this run (-nobuild): build/plugin/nbm.so of $so_start"
so_end=$(sotime)
[ "$so_end" = "$so_start" ] ||
  plugin_state="$plugin_state; WARNING: build/plugin/nbm.so was rebuilt while the benchmark ran (now of $so_end), so the runs did not all use the same plugin"
dirty=$(git -C "$repo" status --porcelain -- plugin edp | awk '{ printf "%s%s", (NR > 1) ? " " : "", $2 }')
{
  echo "# Script-level benchmark: the bouncing plate through FreeFem++"
  echo
  echo "Produced by \`bash bench/script-timing.sh${args:+ $args}\` on $(date -u +%Y-%m-%d), commit $(git -C "$repo" rev-parse --short HEAD)"
  echo "($(nproc) cores, $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo),"
  echo "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $(FreeFem++ 2>&1 | head -n 1 | sed 's/ *(.*)//'))."
  echo "Plugin $plugin_state."
  if [ -n "$dirty" ]; then
    echo "Uncommitted changes in plugin/ or edp/ when it ran (so in the plugin or scripts timed): $dirty."
  fi
  echo "Load average (1, 5, 15 min) at the start: $load_start; at the end: $load_end; 1-min load"
  echo "before the runs: $(awk -F, 'NR > 1 { if (min == "" || $6 < min) min = $6; if ($6 > max) max = $6 } END { print min " to " max }' "$raw")"
  echo "(on $(nproc) cores, above about 0.5 other work shared the machine and the times are perturbed)."
  echo "Spread of the times of one configuration over the rounds (max / min): up to"
  echo "$(awk -F, 'NR > 1 { k = $2 SUBSEP $3 SUBSEP $4; if (!(k in lo) || $5 < lo[k]) lo[k] = $5; if ($5 > hi[k]) hi[k] = $5 }
    END { for (k in lo) { split(k, p, SUBSEP); r = hi[k] / lo[k]; if (p[3] + 0 == 0) { if (r > f) f = r } else if (r > w) w = r }
          printf "%.2f for the whole runs, %.2f for the T = 0 runs", w, f }' "$raw")."
  echo "Total time of the benchmark: $(( $(date +%s) - start )) s."
  echo
  echo "Problem: plate-setup.idp defaults (E = 1000, nu = 0.3, rho = 1, g = 10, width 1, height 0.5,"
  echo "h0 = 0.1; the impact is at t = 0.141), P1, dt = $dt at every mesh size, T = $T,"
  echo "\`-vtkFrames 0 -snapshots 0\`. Methods: \`edp/bouncing-plate.edp\` (NBM, \`-mass consistent\`: the"
  echo "paper's; \`-mass redistributed\`: the massless boundary), \`edp/bouncing-plate-nitsche.edp -theta 1\`"
  echo "(gamma0 E = 0.1; semi-smooth Newton per step, FreeFEM \`sparsesolver\` refactorisation whenever"
  echo "the active set changes). Every configuration ran $repeat times (rounds interleaved), once with"
  echo "T = $T and once with T = 0; the minimum of each is kept. \"fixed\" is the T = 0 run (FreeFem++"
  echo "start, gmsh, assembly, NBM construction or Nitsche's first factorisation, step-0 output, the"
  echo "history plot); \"loop\" = whole - fixed, the time steps with the per-step script work of the"
  echo "plate scripts (diagnostics and two CSV rows per step, the same for every method). Steps in"
  echo "contact: steps with n_active > 0 in the run's CSV. Raw data: out/script-timing/runs.csv."
  echo
  echo "## Wall time per simulated second"
  echo
  echo "| method | lc | triangles | dofs | contact nodes | steps (in contact) | fixed (s) | whole run (s) | loop (s) | loop per simulated s (s) | loop per step (ms) | Newton iterations, refactorisations |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  for i in "${!methods[@]}"; do
    awk -F, -v m="${methods[$i]}" -v label="${labels[$i]}" 'NR > 1 && $1 == m {
      printf "| %s | %s | %s | %s | %s | %s (%s) | %.2f | %.2f | %.2f | %.3g | %.3g | %s |\n", label, $2, $3, $4, $5, $6, $7,
             $8, $9, $10, $11, $12, ($13 == "") ? "-" : $13 ", " $14 }' "$table"
  done
  echo
  echo "## Nitsche / NBM (the issue's target: at least 20)"
  echo
  echo "| lc | dofs | loop: Nitsche / NBM paper | loop: Nitsche / NBM massless | whole run: Nitsche / NBM paper | whole run: Nitsche / NBM massless |"
  echo "|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { loop[$1, $2] = $10; whole[$1, $2] = $9; dofs[$2] = $4; if (!($2 in seen)) { seen[$2] = 1; order[++n] = $2 } }
    END {
      for (i = 1; i <= n; i++) {
        lc = order[i]
        printf "| %s | %s | %.1f | %.1f | %.1f | %.1f |\n", lc, dofs[lc],
          loop["nitsche", lc] / loop["nbm", lc], loop["nitsche", lc] / loop["nbm-massless", lc],
          whole["nitsche", lc] / whole["nbm", lc], whole["nitsche", lc] / whole["nbm-massless", lc]
      }
    }' "$table"
} > "$report.tmp"
mv "$report.tmp" "$report"
cat "$report"
echo "script-timing: wrote $report"
