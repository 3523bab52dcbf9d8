#!/usr/bin/env bash
# libFuzzer run of the nbm core: builds the fuzz targets in ./build-fuzz with
# clang (ASan + UBSan, any report fatal) and runs each target for its share of
# the given total time; fails on any crash, sanitizer report, hang (an input
# taking more than 10 s), leak or violated property.
#   bash tests/fuzz/run.sh [seconds]          # default: 60 s in total
#
# Targets (sources in tests/fuzz/, properties in their headers):
#   fuzz_contact_set   nbm::ContactSet validation (dofs, normals, gaps, fixed)
#   fuzz_lcp           nbm::LcpSolver::solve on random SPD matrices, n = 1..12
#   fuzz_solver        a few steps of nbm::Solver on small random problems
#
# Corpus: the committed seeds and reproducers in tests/fuzz/corpus/<target>/
# are read (and re-run first, as regression tests) but never written; new
# inputs go to build-fuzz/fuzz-corpus/<target>/, kept from run to run, so
# repeated runs go deeper. A crash leaves build-fuzz/fuzz-artifacts/<target>-crash-*
# (or -timeout-*, -leak-*); reproduce it with
#   build-fuzz/fuzz/<target> <file>
# and, once fixed, copy the file into tests/fuzz/corpus/<target>/.
#
# Longer runs: give more seconds (bash tests/fuzz/run.sh 3600: 20 min per
# target), or run one target with any libFuzzer flags, e.g. two processes
# for two hours:
#   build-fuzz/fuzz/fuzz_solver build-fuzz/fuzz-corpus/fuzz_solver \
#     tests/fuzz/corpus/fuzz_solver -max_total_time=7200 -timeout=10 \
#     -max_len=2048 -jobs=2 -workers=2 -artifact_prefix=build-fuzz/fuzz-artifacts/
# To shrink the grown corpus into a few seeds worth committing:
#   build-fuzz/fuzz/<target> -merge=1 <new dir> build-fuzz/fuzz-corpus/<target>
#
# Needs clang with libFuzzer: Debian packages clang-14 and libclang-rt-14-dev.
# The last line is "fuzz: N passed, M failed (E executions)" (one per target).
set -u
repo=$(cd "$(dirname "$0")/../.." && pwd)
total=${1:-60}
bdir="$repo/build-fuzz"
targets=(fuzz_contact_set fuzz_lcp fuzz_solver)
start=$SECONDS

execs_total=0
finish() {  # finish <passed> <failed>
  echo "fuzz: total time $((SECONDS - start)) s"
  echo "fuzz: $1 passed, $2 failed ($execs_total executions)"
  [ "$2" -eq 0 ]
  exit
}

if ! [[ "$total" =~ ^[0-9]+$ ]] || [ "$total" -lt 1 ]; then
  echo "usage: bash tests/fuzz/run.sh [seconds >= 1]"
  finish 0 1
fi
cxx=$(command -v clang++-14 || command -v clang++) || {
  echo "fuzz: clang++ not found: install the Debian packages clang-14 and libclang-rt-14-dev"
  finish 0 1
}

echo "fuzz: configuring and building $bdir with $cxx"
mkdir -p "$bdir"
if ! cmake -S "$repo" -B "$bdir" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DNBM_FUZZ=ON -DNBM_EIGEN_BLAS=OFF -DNBM_BUILD_TESTS=OFF \
      -DNBM_BUILD_BENCH=OFF -DNBM_SANITIZE=OFF >"$bdir/configure.log" 2>&1; then
  cat "$bdir/configure.log"
  echo "fuzz: configure failed"
  finish 0 1
fi
if ! cmake --build "$bdir" -j "$(nproc)" --target nbm_fuzzers >"$bdir/build.log" 2>&1; then
  tail -n 60 "$bdir/build.log"
  echo "fuzz: build failed (full log: $bdir/build.log; libFuzzer needs libclang-rt-14-dev)"
  finish 0 1
fi
echo "fuzz: built in $((SECONDS - start)) s"

share=$((total / ${#targets[@]}))
[ "$share" -ge 1 ] || share=1
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
passed=0 failed=0
mkdir -p "$bdir/fuzz-artifacts" "$bdir/fuzz-logs"
for t in "${targets[@]}"; do
  mkdir -p "$bdir/fuzz-corpus/$t" "$repo/tests/fuzz/corpus/$t"
  log="$bdir/fuzz-logs/$t.log"
  "$bdir/fuzz/$t" "$bdir/fuzz-corpus/$t" "$repo/tests/fuzz/corpus/$t" \
    -max_total_time="$share" -timeout=10 -max_len=2048 -rss_limit_mb=2048 \
    -artifact_prefix="$bdir/fuzz-artifacts/$t-" -print_final_stats=1 >"$log" 2>&1
  code=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  execs_total=$((execs_total + ${execs:-0}))
  if [ $code -eq 0 ]; then
    echo "fuzz: $t: OK, ${execs:-?} executions in ${share} s"
    passed=$((passed + 1))
  else
    tail -n 60 "$log"
    echo "fuzz: $t: FAILED (exit code $code, ${execs:-?} executions; log $log)"
    ls -1 "$bdir/fuzz-artifacts/$t-"* 2>/dev/null | sed 's/^/fuzz:   reproducer: /'
    failed=$((failed + 1))
  fi
done
finish "$passed" "$failed"
