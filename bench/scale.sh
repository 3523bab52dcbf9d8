#!/usr/bin/env bash
# Issue 14's benchmarks of large contact sets and 3D (bench/bench_step.cpp,
# BM_Scale*): for every case, the plain steps and factorization once, then per
# contact set the NBM setup, free flight and a sweep (a contact front crossing
# the contact set in 20 steps, the active set changing at every step) for the
# three schemes, and the penalty step that refactorises. Writes a Markdown
# section (ratios, targets met or missed, exponents in n_c, times) that
# bench/run.sh puts into bench/RESULTS.md, and its raw data next to it (.csv).
#
#   bash bench/scale.sh                      the default cases below (RESULTS.md)
#   bash bench/scale.sh "CASES" SECTION      CASES: "body:order:dofs:pct,pct,..." ...
#     body 0 plate (W/H = 2), 1 strip (W/H = 80: 2000 x 25 cells at 1e5 P1 dofs),
#     2 block (nx = ny = 4 nz tetrahedra); pct: % of the bottom face in contact
#     (6, 12, 25, 50, 100), 200: bottom and top faces. SECTION: the output file.
#   SCALE_MILLION=1 adds the 3D block of 1e6 P1 dofs (bottom face: 1e4 contact
#     nodes). Its factor alone holds 15 GB of this machine's 24: the NBM
#     benchmarks run there are SCALE_MILLION_NBM (default: the implicit sweep,
#     which shows whether the paper NBM fits, the massless boundary's and the
#     explicit scheme's; the penalty scheme would refactorise 15 GB at each of
#     its 20 steps), each stopped after MILLION_TIMEOUT seconds (default 3600).
#   TIMEOUT (default 900): the other benchmark processes' time limit; one
#     stopped, failed or out of memory is reported as not finished.
#   ROUNDS (default 1): rounds per benchmark, the fastest kept.
#   SCALE_NBM="ScaleNbmNewmarkStepSweep ...": the NBM benchmarks run (default:
#     all eight); without ScaleNbmSetup the setup is the one the implicit sweep
#     timed before its steps (its setup_us), e.g. for the 1e6-dof block, where a
#     process per benchmark costs a setup of many minutes each.
#   REPORT_ONLY=1: no run, the section written again from SECTION's raw data
#     and the facts of the run that made it (SECTION's .csv.info: date, commit,
#     rounds, duration, load, BLAS, clock), e.g. after the text around the
#     tables changed, or a run stopped by hand.
#   CLOCK=cpu: the ratios from the CPU time of the benchmark's thread instead
#     of the wall-clock time (default real): on a machine loaded by other work,
#     with OPENBLAS_NUM_THREADS=1 (the only thread then does all the work).
# The build is expected (bench/run.sh builds); OPENBLAS_NUM_THREADS is passed on.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
default_cases="0:1:100000:25,50,100,200 1:1:100000:6,12,25,50,100 2:1:30000:6,12,25,50,100,200 2:2:30000:25,100"
cases=${1:-$default_cases}
if [ "${SCALE_MILLION:-0}" = 1 ]; then cases="$cases 2:1:1000000:100"; fi
section=${2:-"$repo/out/bench/scale.md"}
bench="$repo/build/bench/nbm_bench"
work="$repo/out/bench/scale"
mkdir -p "$work" "$(dirname "$section")"
raw="${section%.md}.csv"
rounds=${ROUNDS:-1}
timeout=${TIMEOUT:-900}
plain=(ScalePlainNewmarkStep ScalePlainExplicitStep ScalePlainFactorization)
nbm=(${SCALE_NBM:-ScaleNbmSetup ScaleNbmNewmarkStepFreeFlight ScaleNbmNewmarkStepSweep ScaleNbmMasslessStepFreeFlight
     ScaleNbmMasslessStepSweep ScaleNbmExplicitStepFreeFlight ScaleNbmExplicitStepSweep ScalePenaltyStepSweep})
million_nbm=(${SCALE_MILLION_NBM:-ScaleNbmNewmarkStepSweep ScaleNbmMasslessStepFreeFlight ScaleNbmMasslessStepSweep
             ScaleNbmExplicitStepFreeFlight ScaleNbmExplicitStepSweep})
million_timeout=${MILLION_TIMEOUT:-3600}
clock=${CLOCK:-real}
header="name,body,order,dofs_arg,pct,dofs,contacts,time_us,held_mb,switch_steps,fallbacks,penalty_factor_us,peak_rss_mb,real_us,cpu_us,setup_us"
info="$raw.info"  # the facts of the run, which the report states
if [ "${REPORT_ONLY:-0}" = 1 ]; then
  . "$info"
else
  echo "$header" > "$raw.rounds"
  run_blas=$("$bench" --blas)
  run_load=$(cut -d' ' -f1 /proc/loadavg)
  run_date=$(date -u +%Y-%m-%d)
  run_commit=$(git -C "$repo" rev-parse --short HEAD)
  run_args="${1:+ \"$1\"}"
  [ "${SCALE_MILLION:-0}" = 1 ] && run_args="$run_args with SCALE_MILLION=1"
  run_clock=$clock
fi
start=$SECONDS

# run NAME BODY ORDER DOFS PCT: one benchmark in its own process, one CSV row
# (time NA if it failed or ran out of time).
run() {
  local name=$1 body=$2 order=$3 dofs=$4 pct=$5 out="$work/$1-$2-$3-$4-$5.csv"
  local filter="^BM_$name/body:$body/order:$order/dofs:$dofs/contact_pct:$pct(/|\$)"
  local limit=$timeout
  [ "$dofs" = 1000000 ] && limit=$million_timeout
  if ! timeout "$limit" "$bench" --benchmark_filter="$filter" --benchmark_format=csv \
         --benchmark_min_time=0.5 > "$out" 2> "$out.err" || ! grep -q '^"BM_' "$out" ||
       grep -q '^"BM_.*,true,' "$out"; then  # no result, or error_occurred (SkipWithError)
    echo "$name,$body,$order,$dofs,$pct,,,NA,,,,,,,," >> "$raw.rounds"
    echo "scale: $name $body:$order:$dofs:$pct failed, was skipped or took more than $limit s" >&2
    return
  fi
  # Google Benchmark's CSV: name,iterations,real_time,cpu_time,time_unit,...,
  # then the counters; columns found by their header.
  awk -F, -v n="$name" -v b="$body" -v o="$order" -v d="$dofs" -v p="$pct" -v clock="$clock" '
    /^name,/ { for (i = 1; i <= NF; i++) { h = $i; gsub(/"/, "", h); col[h] = i }; next }
    /^"BM_/ {
      u = $col["time_unit"]; f = (u == "ms") ? 1000 : (u == "ns") ? 1e-3 : (u == "s") ? 1e6 : 1
      real = $col["real_time"] * f; cpu = $col["cpu_time"] * f
      printf "%s,%s,%s,%s,%s,%d,%d,%.6g,%.3f,%s,%s,%s,%.0f,%.6g,%.6g,%s\n", n, b, o, d, p, $col["dofs"],
             $col["contacts"], clock == "cpu" ? cpu : real, $col["held_MB"], get("switch_steps"),
             get("fallbacks"), get("penalty_factor_us"), $col["peak_rss_MB"], real, cpu, get("setup_us")
    }
    function get(c) { return (c in col) ? $col[c] : "" }' "$out" >> "$raw.rounds"
}

[ "${REPORT_ONLY:-0}" = 1 ] && rounds=0
for round in $(seq "$rounds"); do
  for c in $cases; do
    IFS=: read -r body order dofs pcts <<< "$c"
    first=${pcts%%,*}
    for name in "${plain[@]}"; do run "$name" "$body" "$order" "$dofs" "$first"; done
    names=("${nbm[@]}")
    [ "$dofs" = 1000000 ] && names=("${million_nbm[@]}")
    for pct in ${pcts//,/ }; do
      for name in "${names[@]}"; do run "$name" "$body" "$order" "$dofs" "$pct"; done
      echo "scale: round $round, case $body:$order:$dofs:$pct done ($((SECONDS - start)) s)"
    done
  done
done
# The fastest round per benchmark (failed rounds only if every round failed).
awk -F, -v OFS=, 'NR == 1 { print; next }
  { k = $1 FS $2 FS $3 FS $4 FS $5
    if (!(k in best)) { order[++n] = k; best[k] = $0; t[k] = $8; next }
    if ($8 != "NA" && (t[k] == "NA" || $8 + 0 < t[k] + 0)) { best[k] = $0; t[k] = $8 } }
  END { for (i = 1; i <= n; i++) print best[order[i]] }' "$raw.rounds" > "$raw"
if [ "${REPORT_ONLY:-0}" != 1 ]; then
  run_rounds=$rounds
  run_seconds=$((SECONDS - start))
  for v in run_blas run_load run_date run_commit run_args run_clock run_rounds run_seconds; do
    printf '%s=%q\n' "$v" "${!v}"
  done > "$info"
fi

# The tables' awk programs read the raw rows with t[name, case, pct] = time;
# without a ScaleNbmSetup row (SCALE_NBM), the setup is the implicit sweep's;
# the massless boundary's setup is the one its sweep timed (ScaleNbmMasslessSetup).
rows_awk='function setup_of_sweep() { if ($1 == "ScaleNbmNewmarkStepSweep" && $16 != "" && (t["ScaleNbmSetup", k, $5] == "" || t["ScaleNbmSetup", k, $5] == "NA")) t["ScaleNbmSetup", k, $5] = $16
  if ($1 == "ScaleNbmMasslessStepSweep" && $16 != "") t["ScaleNbmMasslessSetup", k, $5] = $16 }'
{
  echo "## Large contact sets and 3D (issue 14)"
  echo
  echo "Produced by \`bash bench/scale.sh$run_args\` on $run_date, commit $run_commit,"
  echo "$run_rounds round(s), $run_seconds s; load average when it started: $run_load on $(nproc) cores (above about 0.5: ratios perturbed by other work)."
  echo "BLAS: $run_blas. Times: $([ "$run_clock" = cpu ] && echo "CPU time of the benchmark thread (CLOCK=cpu)" || echo "wall clock")."
  echo "Bodies: the plate (bench/plate.cpp, W/H = 2), the strip (the same, W/H = 80), the block"
  echo "(bench/block.cpp: tetrahedra, nx = ny = 4 nz cells, bottom face 1 x 1). Contact: pct % of the"
  echo "bottom face (along x), or 200: bottom and top faces (the top nodes never touch). Sweep: the"
  echo "body falls at 0.1 onto an obstacle inclined along x (3D: along x + y/4), so that the contact front crosses the"
  echo "contact set in 20 steps (implicit dt = 2e-4; explicit: half the critical step of the row-sum"
  echo "lumped mass, the same for the plain explicit step); time per step over those 20 steps, memory"
  echo "held after them. Free flight: the obstacle out of reach. Penalty: average-acceleration"
  echo "Newmark with a penalty on the penetrating nodes, refactorising (numerically, the symbolic"
  echo "analysis reused) at every active-set change; break-even: the number of changing steps after"
  echo "which NBM (setup + steps) costs less than the penalty scheme (a plain factorization + steps)."
  echo "Explicit schemes need a positive row-sum lumped mass, which P2 tetrahedra do not have: '-'."
  echo "Ratios against the plain contact-free step of the same matrices, same run. Raw data:"
  echo "${raw#"$repo"/} (times in us, memory in MB: held = heap growth of the solver objects)."
  echo
  echo "| body | order | dofs | n_c | setup / factorization | memory after the sweep / plain | free flight / plain | changing step / plain | massless setup / factorization | massless memory / plain | massless free flight / plain | massless changing / plain | explicit free flight / plain | explicit changing / plain | penalty changing / plain | NBM / penalty step | break-even (steps) | steps with a change | fallbacks | memory held (MB) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, "$rows_awk"'
    function r(a, b) { return (a == "" || a == "NA" || b == "" || b == "NA" || b + 0 == 0) ? "-" : sprintf("%.2f", a / b) }
    NR > 1 { k = $2 FS $3 FS $4; t[$1, k, $5] = $8; setup_of_sweep(); m[$1, k, $5] = $9; sw[$1, k, $5] = $10; fb[$1, k, $5] = $11
             pf[$1, k, $5] = $12; if ($1 ~ /^ScaleNbm|^ScalePenalty/) { if ($7 != "") nc[k, $5] = $7; if (!((k, $5) in seen)) { seen[k, $5] = 1; rows[++n] = k FS $5 } }
             if ($1 ~ /^ScalePlain/) { plain[$1, k] = $8; pm[$1, k] = $9; if ($6 != "") dofs[k] = $6 } }
    END {
      split("plate strip block", body, " ")
      for (i = 1; i <= n; i++) {
        split(rows[i], f, FS); k = f[1] FS f[2] FS f[3]; p = f[4]
        pn = plain["ScalePlainNewmarkStep", k]; pe = plain["ScalePlainExplicitStep", k]
        pfac = plain["ScalePlainFactorization", k]
        sweep = t["ScaleNbmNewmarkStepSweep", k, p]; pen = t["ScalePenaltyStepSweep", k, p]
        setup = t["ScaleNbmSetup", k, p]
        be = "-"
        if (sweep != "NA" && pen != "NA" && setup != "NA" && sweep != "" && pen != "" && setup != "")
          be = (pen + 0 > sweep + 0) ? sprintf("%.0f", (setup - pfac) / (pen - sweep)) : "never"
        printf "| %s | P%s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
          body[f[1] + 1], f[2], dofs[k], nc[k, p], r(setup, pfac),
          r(m["ScaleNbmNewmarkStepSweep", k, p], pm["ScalePlainNewmarkStep", k]),
          r(t["ScaleNbmNewmarkStepFreeFlight", k, p], pn), r(sweep, pn),
          r(t["ScaleNbmMasslessSetup", k, p], pfac),
          r(m["ScaleNbmMasslessStepSweep", k, p], pm["ScalePlainNewmarkStep", k]),
          r(t["ScaleNbmMasslessStepFreeFlight", k, p], pn), r(t["ScaleNbmMasslessStepSweep", k, p], pn),
          r(t["ScaleNbmExplicitStepFreeFlight", k, p], pe), r(t["ScaleNbmExplicitStepSweep", k, p], pe),
          r(pen, pn), r(sweep, pen), be,
          (sw["ScaleNbmNewmarkStepSweep", k, p] == "") ? "-" : sprintf("%.0f %%", 100 * sw["ScaleNbmNewmarkStepSweep", k, p]),
          (fb["ScaleNbmNewmarkStepSweep", k, p] == "") ? "-" : fb["ScaleNbmNewmarkStepSweep", k, p],
          (m["ScaleNbmNewmarkStepSweep", k, p] == "") ? "-" : m["ScaleNbmNewmarkStepSweep", k, p]
      }
    }' "$raw"
  echo
  echo "### Targets of issue 14"
  echo
  echo "Contact sets of about 2000 nodes (1500 to 2500 here) and below 5e5 dofs: changing step <= 3x a"
  echo "plain step, free flight <= 1.2x, setup <= 3x a factorization, memory <= 2x; the 3D block of"
  echo "about 1e6 dofs: changing step <= 5x, setup <= 5x, memory <= 2x. Each case with both mass"
  echo "treatments: the paper's NBM (mass on the contact nodes), then the massless boundary."
  echo
  awk -F, "$rows_awk"'
    NR > 1 { k = $2 FS $3 FS $4; t[$1, k, $5] = $8; setup_of_sweep(); m[$1, k, $5] = $9
             if ($1 ~ /^ScaleNbm/ && $7 != "") { nc[k, $5] = $7; if (!((k, $5) in seen)) { seen[k, $5] = 1; rows[++n] = k FS $5 } }
             if ($1 ~ /^ScalePlain/) { plain[$1, k] = $8; pm[$1, k] = $9; if ($6 != "") dofs[k] = $6 } }
    function row(what, a, b, target) {
      if (a == "" || a == "NA" || b == "" || b == "NA") { printf "- %s: not measured (did not finish): missed\n", what; return }
      v = a / b
      printf "- %s: %.2f (target <= %g): %s\n", what, v, target, v <= target ? "met" : sprintf("missed by a factor %.2f", v / target)
    }
    END {
      split("plate strip block", body, " ")
      for (i = 1; i <= n; i++) {
        split(rows[i], f, FS); k = f[1] FS f[2] FS f[3]; p = f[4]; c = nc[k, p] + 0
        big = dofs[k] + 0 >= 5e5
        if (!big && (c < 1500 || c > 2500)) continue
        name = sprintf("%s P%s, %s dofs, %d contact nodes", body[f[1] + 1], f[2], dofs[k], c)
        pn = plain["ScalePlainNewmarkStep", k]; pf = plain["ScalePlainFactorization", k]
        pmem = pm["ScalePlainNewmarkStep", k]
        # The paper NBM (mass on the contact nodes), then the massless boundary.
        row(name ", changing step / plain", t["ScaleNbmNewmarkStepSweep", k, p], pn, big ? 5 : 3)
        if (!big) row(name ", free flight / plain", t["ScaleNbmNewmarkStepFreeFlight", k, p], pn, 1.2)
        row(name ", setup / factorization", t["ScaleNbmSetup", k, p], pf, big ? 5 : 3)
        row(name ", memory / plain", m["ScaleNbmNewmarkStepSweep", k, p], pmem, 2)
        row(name ", massless boundary: changing step / plain", t["ScaleNbmMasslessStepSweep", k, p], pn, big ? 5 : 3)
        if (!big) row(name ", massless boundary: free flight / plain", t["ScaleNbmMasslessStepFreeFlight", k, p], pn, 1.2)
        row(name ", massless boundary: setup / factorization", t["ScaleNbmMasslessSetup", k, p], pf, big ? 5 : 3)
        row(name ", massless boundary: memory / plain", m["ScaleNbmMasslessStepSweep", k, p], pmem, 2)
        listed++
      }
      if (!listed) print "(No case of this run is in those ranges.)"
    }' "$raw"
  echo
  echo "### Growth with the contact set at fixed dofs: fitted exponent p of cost ~ n_c^p"
  echo
  echo "Least squares over the contact sets of each case; the step and setup costs are the excess"
  echo "over the plain step and factorization (what NBM adds), memory is what the solver holds."
  echo
  echo "| body | order | dofs | n_c range | setup - factorization | changing step - plain | massless changing - plain | free flight - plain | memory held |"
  echo "|---|---|---|---|---|---|---|---|---|"
  awk -F, "$rows_awk"'
    NR > 1 { k = $2 FS $3 FS $4; t[$1, k, $5] = $8; setup_of_sweep(); m[$1, k, $5] = $9
             if ($1 ~ /^ScaleNbm/ && $7 != "") { nc[k, $5] = $7; if (!((k, $5) in seen)) { seen[k, $5] = 1; pcts[k] = pcts[k] " " $5 } }
             if ($1 ~ /^ScalePlain/) { plain[$1, k] = $8; if ($6 != "") dofs[k] = $6; keys[k] = 1 } }
    # slope of log(value - base) against log(n_c) over the contact sets of k
    function fit(name, k, base, mem,   np, i, p, v, x, y, sx, sy, sxx, sxy, q) {
      np = split(pcts[k], q, " "); sx = sy = sxx = sxy = 0; cnt = 0
      for (i = 1; i <= np; i++) {
        p = q[i]; v = mem ? m[name, k, p] : t[name, k, p]
        if (v == "" || v == "NA" || v - base <= 0) continue
        x = log(nc[k, p]); y = log(v - base); cnt++; sx += x; sy += y; sxx += x * x; sxy += x * y
      }
      return cnt > 1 ? sprintf("%.2f", (cnt * sxy - sx * sy) / (cnt * sxx - sx * sx)) : "-"
    }
    END {
      split("plate strip block", body, " ")
      for (k in keys) {
        split(k, f, FS); np = split(pcts[k], q, " "); if (np < 2) continue
        lo = hi = nc[k, q[1]]; for (i = 2; i <= np; i++) { if (nc[k, q[i]] + 0 < lo + 0) lo = nc[k, q[i]]; if (nc[k, q[i]] + 0 > hi + 0) hi = nc[k, q[i]] }
        pn = plain["ScalePlainNewmarkStep", k]
        printf "| %s | P%s | %s | %s-%s | %s | %s | %s | %s | %s |\n", body[f[1] + 1], f[2], dofs[k], lo, hi,
          fit("ScaleNbmSetup", k, plain["ScalePlainFactorization", k], 0),
          fit("ScaleNbmNewmarkStepSweep", k, pn, 0), fit("ScaleNbmMasslessStepSweep", k, pn, 0),
          fit("ScaleNbmNewmarkStepFreeFlight", k, pn, 0), fit("ScaleNbmNewmarkStepSweep", k, 0, 1)
      }
    }' "$raw" | sort
  echo
  echo "### Times"
  echo
  echo "| benchmark | body | order | dofs | contact % | n_c | time (us) | held (MB) | peak RSS (MB) | steps with a change | fallbacks |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | P%s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $6, $5, $7, $8, $9, $13, $10, $11 }' "$raw"
} > "$section.tmp"
mv "$section.tmp" "$section"
echo "scale: wrote $section ($((SECONDS - start)) s)"
