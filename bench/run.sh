#!/usr/bin/env bash
# Runs the core benchmarks and writes bench/RESULTS.md (ratios NBM / plain
# measured side by side, fitted scaling exponents, peak memory) and
# bench/scaling.png (log-log step time against dofs). The script-level
# benchmark (whole FreeFem++ runs, NBM against Nitsche) is bench/script-timing.sh,
# which writes bench/RESULTS-scripts.md; the report points to it.
#
#   bash bench/run.sh                 P1 and P2, 1e3, 1e4 and 1e5 dofs (about 10 minutes)
#   bash bench/run.sh "1000 10000"    other sizes
#   bash bench/run.sh SIZES ORDERS REPORT
#                                     ORDERS: "1", "2" or "1 2" (default); REPORT: where
#                                     the report goes instead of bench/RESULTS.md (its raw
#                                     data and plot go next to it, as .csv and .png). The
#                                     10^6-dof run of bench/million.md:
#   bash bench/run.sh 1000000 1 out/bench/million/RESULTS.md      (about 25 minutes)
#
# Every benchmark runs in its own process so that its peak resident memory
# (VmHWM) is its own. The machine's noise (other jobs, a virtualised CPU)
# moves single runs by 10-40 %, so every size is measured in ROUNDS rounds
# (environment, default 3), the benchmarks interleaved within a round, and
# the report takes each benchmark's fastest round (the spread, slowest /
# fastest, is in the raw data and the times table). Raw results: out/bench/*.csv.
#
# Then bench/scale.sh (issue 14: large contact sets, the 2D strip, the 3D
# blocks, the sweep in n_c, the penalty break-even; about 1 hour more with its
# default cases) writes its section of the report; SCALE=0 skips it,
# SCALE_CASES="..." replaces its cases, SCALE_MILLION=1 adds the 1e6-dof block.
# REPORT_ONLY=1: no benchmark run; the report (and the scale section) written
# again from the raw data of the last run and its facts (raw.csv.info: date,
# commit, load, BLAS, rounds), e.g. after bench/why.md or bench/why-scale.md
# changed.
# The report says which BLAS ran (scripts/install-deps.sh selects OpenBLAS)
# and with how many threads: OPENBLAS_NUM_THREADS from the environment if set,
# else OpenBLAS's default (one per core); the benchmarks run one at a time, so
# its threads have the cores to themselves.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
sizes=${1:-"1000 10000 100000"}
orders=${2:-"1 2"}
report=${3:-"$repo/bench/RESULTS.md"}
report_only=${REPORT_ONLY:-0}
if [ "$report_only" != 1 ]; then
  bash "$repo/scripts/install-deps.sh" >/dev/null
  bash "$repo/scripts/build.sh" >/dev/null
fi
bench="$repo/build/bench/nbm_bench"
work="$repo/out/bench"
mkdir -p "$work" "$(dirname "$report")"
if [ "$report" = "$repo/bench/RESULTS.md" ]; then
  raw="$work/raw.csv"
  plot="$repo/bench/scaling.png"
else
  raw="${report%.md}.csv"
  plot="${report%.md}.png"
fi
info="$raw.info"  # the facts of the run, which the report states
if [ "$report_only" = 1 ]; then
  . "$info"
  sizes=""  # no run
else
  run_rounds=${ROUNDS:-3}
  run_load=$(cut -d' ' -f1 /proc/loadavg)  # other work on the machine skews the ratios
  run_blas=$("$bench" --blas)
  run_date=$(date -u +%Y-%m-%d)
  run_commit=$(git -C "$repo" rev-parse --short HEAD)
  run_args="${1:+ \"$1\"}${2:+ \"$2\"}${3:+ $3}"
  for v in run_rounds run_load run_blas run_date run_commit run_args; do printf '%s=%q\n' "$v" "${!v}"; done > "$info"
  echo "name,order,dofs,contacts,time_us,held_mb,solves_per_step,switch_steps,peak_rss_mb" > "$raw.rounds"
fi
rounds=$run_rounds

names=(PlainNewmarkStep PlainExplicitStep PlainFactorization NbmNewmarkStepFreeFlight
       NbmNewmarkStepBouncing NbmMasslessStepFreeFlight NbmMasslessStepBouncing
       NbmExplicitStepFreeFlight NbmExplicitStepBouncing NbmSetup)
for dofs in $sizes; do
  for order in $orders; do
    for round in $(seq "$rounds"); do
      for name in "${names[@]}"; do
        out="$work/$name-$order-$dofs-$round.csv"
        "$bench" --benchmark_filter="^BM_$name/order:$order/dofs:$dofs(/|\$)" \
          --benchmark_format=csv --benchmark_min_time=0.5 > "$out" 2>/dev/null
        # Columns of Google Benchmark's CSV: name,iterations,real_time,cpu_time,
        # time_unit,...,then the counters in alphabetical order.
        awk -F, -v n="$name" -v o="$order" '
          /^name,/ { for (i = 1; i <= NF; i++) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
          /^"BM_/ {
            t = $col["real_time"]; u = $col["time_unit"]
            if (u == "ms") t *= 1000; else if (u == "ns") t /= 1000; else if (u == "s") t *= 1e6
            printf "%s,%s,%d,%d,%.6g,%.2f,%s,%s,%.0f\n", n, o, $col["dofs"], $col["contacts"], t,
                   $col["held_MB"], ("solves_per_step" in col) ? $col["solves_per_step"] : "",
                   ("switch_steps" in col) ? $col["switch_steps"] : "", $col["peak_rss_MB"]
          }' "$out" >> "$raw.rounds"
      done
    done
    echo "bench: order $order, $dofs dofs done ($rounds rounds)"
  done
done
# Per benchmark and size: the fastest round, its spread (slowest / fastest)
# and the largest peak RSS, in the order of the rounds file.
awk -F, -v OFS=, 'NR == 1 { print $0, "spread"; next }
  { k = $1 FS $2 FS $3
    if (!(k in best)) { order[++n] = k; best[k] = $0; lo[k] = hi[k] = $5 + 0; rss[k] = $9 + 0; next }
    if ($5 + 0 < lo[k]) { lo[k] = $5 + 0; best[k] = $0 }
    if ($5 + 0 > hi[k]) hi[k] = $5 + 0
    if ($9 + 0 > rss[k]) rss[k] = $9 + 0 }
  END { for (i = 1; i <= n; i++) { k = order[i]; split(best[k], f, FS); f[9] = rss[k]
          line = f[1]; for (j = 2; j <= 9; j++) line = line OFS f[j]
          print line, sprintf("%.2f", hi[k] / lo[k]) } }' "$raw.rounds" > "$raw"

# Ratios per (order, dofs), exponents per benchmark, the report.
{
  echo "# Benchmark results"
  echo
  echo "Produced by \`bash bench/run.sh$run_args\` on $run_date, commit $run_commit"
  echo "($(nproc) cores, $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo),"
  echo "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))."
  echo "BLAS (CHOLMOD's): $run_blas."
  echo "Load average when the run started: $run_load (on $(nproc) cores, anything above about 0.5 means the ratios"
  echo "below are perturbed by other work; rerun on a quiet machine)."
  echo "Plane-strain plate (bench/plate.cpp, width 2 x height 1, Lagrange P1/P2 triangles), contact on the bottom edge;"
  echo "implicit dt = 2e-4, bouncing runs restart every 250 steps (fall, impact, rebound); explicit"
  echo "dt = half the critical step. Times are wall-clock per step (per factorization or setup for"
  echo "those rows), the fastest of $rounds rounds in which every benchmark ran in its own process,"
  echo "interleaved with the others; the step rows start after one untimed first step (its time,"
  echo "which includes the dense factorizations of the first active set, is the first_step_us"
  echo "counter of out/bench/*.csv); memory is what the solver objects hold"
  echo "(heap growth after the plate was assembled, glibc mallinfo2). Raw data: ${raw#"$repo"/}."
  echo
  echo "Whole FreeFem++ runs (wall time per simulated second of the bouncing plate, NBM against"
  echo "Nitsche, four mesh sizes): [RESULTS-scripts.md](RESULTS-scripts.md), by \`bash bench/script-timing.sh -lc \"0.058 0.029 0.0145 0.00725\" -repeat 2\`."
  echo
  echo "## Ratios NBM / plain (same matrices, same factorization library, same run)"
  echo
  echo "| order | dofs | contact nodes | implicit bouncing | implicit free flight | massless bouncing | massless free flight | setup / factorization | explicit bouncing | explicit free flight | memory (NBM bouncing / plain) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { k = $2 "," $3; t[$1, k] = $5; m[$1, k] = $6; c[k] = ($4 > c[k]) ? $4 : c[k]; d[k] = $3; o[k] = $2; keys[k] = 1 }
    END {
      n = 0; for (k in keys) list[++n] = k
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
        if (o[list[j]] < o[list[i]] || (o[list[j]] == o[list[i]] && d[list[j]] + 0 < d[list[i]] + 0)) { x = list[i]; list[i] = list[j]; list[j] = x }
      for (i = 1; i <= n; i++) {
        k = list[i]; p = t["PlainNewmarkStep", k]; e = t["PlainExplicitStep", k]
        printf "| P%s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f | %.2f | %.2f |\n", o[k], d[k], c[k],
          t["NbmNewmarkStepBouncing", k] / p, t["NbmNewmarkStepFreeFlight", k] / p,
          t["NbmMasslessStepBouncing", k] / p, t["NbmMasslessStepFreeFlight", k] / p,
          t["NbmSetup", k] / t["PlainFactorization", k],
          t["NbmExplicitStepBouncing", k] / e, t["NbmExplicitStepFreeFlight", k] / e,
          m["NbmNewmarkStepBouncing", k] / m["PlainNewmarkStep", k]
      }
    }' "$raw"
  echo
  echo "## Targets of the benchmark issue, at the largest size run (P1)"
  echo
  awk -F, 'NR > 1 && $2 == 1 { if ($3 + 0 > big) big = $3 + 0; t[$1, $3] = $5; m[$1, $3] = $6 }
    END {
      k = big; p = t["PlainNewmarkStep", k]; e = t["PlainExplicitStep", k]
      row("implicit NBM step / plain, bouncing", t["NbmNewmarkStepBouncing", k] / p, 1.3)
      row("implicit NBM step / plain, free flight", t["NbmNewmarkStepFreeFlight", k] / p, 1.1)
      row("massless-boundary NBM step / plain, bouncing", t["NbmMasslessStepBouncing", k] / p, 1.3)
      row("massless-boundary NBM step / plain, free flight", t["NbmMasslessStepFreeFlight", k] / p, 1.1)
      row("NBM setup / plain factorization", t["NbmSetup", k] / t["PlainFactorization", k], 5)
      row("explicit NBM step / plain explicit step (bouncing)", t["NbmExplicitStepBouncing", k] / e, 1.5)
      row("NBM memory / plain (implicit, bouncing)", m["NbmNewmarkStepBouncing", k] / m["PlainNewmarkStep", k], 2)
      printf "\n(%d dofs.)\n", k
    }
    function row(what, value, target) {
      printf "- %s: %.2f (target <= %g): %s\n", what, value, target,
             value <= target ? "met" : sprintf("missed by a factor %.2f", value / target)
    }' "$raw"
  cat "$repo/bench/why.md"
  echo
  echo "## Times"
  echo
  echo "Fastest of $rounds rounds; spread: slowest / fastest round."
  echo
  echo "| benchmark | order | dofs | time per step (us) | spread | memory held (MB) | peak RSS of the process (MB) | solves per step | steps with an active-set change |"
  echo "|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | P%s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $5, $10, $6, $9, $7, $8 }' "$raw"
  echo
  echo "## Scaling: fitted exponent of time against dofs (least squares over the sizes run)"
  echo
  echo "| benchmark | P1 | P2 |"
  echo "|---|---|---|"
  awk -F, 'NR > 1 { x = log($3); y = log($5); k = $1 SUBSEP $2; n[k]++; sx[k] += x; sy[k] += y; sxx[k] += x * x; sxy[k] += x * y; names[$1] = 1 }
    END {
      for (b in names) {
        line = "| " b
        for (o = 1; o <= 2; o++) {
          k = b SUBSEP o
          line = line " | " ((n[k] > 1) ? sprintf("%.2f", (n[k] * sxy[k] - sx[k] * sy[k]) / (n[k] * sxx[k] - sx[k] * sx[k])) : "-")
        }
        print line " |"
      }
    }' "$raw" | sort
} > "$report.tmp"

gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1100,700 font ',10'
set output '$plot'
set logscale xy; set grid; set key top left
set xlabel 'dofs'; set ylabel 'time per step (us)'
set title 'Step time against problem size (P1), bench/run.sh'
plot for [b in "PlainNewmarkStep NbmNewmarkStepBouncing NbmNewmarkStepFreeFlight NbmMasslessStepBouncing PlainExplicitStep NbmExplicitStepBouncing"] \
  '< awk -F, -v b='.b.' "\\\$1 == b && \\\$2 == 1" $raw' using 3:5 with linespoints lw 2 title b
GP
if [ "${SCALE:-1}" != 0 ]; then
  scale_section="${report%.md}-scale.md"
  [ "$report" = "$repo/bench/RESULTS.md" ] && scale_section="$work/scale.md"
  bash "$repo/bench/scale.sh" "${SCALE_CASES:-}" "$scale_section"
  { echo; cat "$scale_section"; echo; cat "$repo/bench/why-scale.md"; } >> "$report.tmp"
fi
if [ "$report" = "$repo/bench/RESULTS.md" ] && [ -f "$repo/bench/million.md" ]; then
  { echo; cat "$repo/bench/million.md"; } >> "$report.tmp"  # the 10^6-dof run, kept as recorded
fi
mv "$report.tmp" "$report"
echo "bench: wrote $report and $plot"
