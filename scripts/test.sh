#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test:
#   1. ctest in ./build: script tests, bad-input catalogue, the shortened long
#      run, restart and robustness tests, the allocation test, benchmark smoke
#      runs (built without the other unit tests: -DNBM_BUILD_UNIT_TESTS=OFF);
#   2. tests/sanitize.sh: the unit tests of the core, under AddressSanitizer +
#      UBSan (./build-sanitize), and the bad-input catalogue and a subset of the
#      script tests again. The unit tests compile (gcc spends most of its time
#      on them) and run in this build only: it checks more (ASan, UBSan on
#      the code under test, LeakSanitizer, Eigen's assertions), and compiling them once saves
#      353 of the optimized build's 667 s (2 cores, at 6823d9d; docs/testing.md);
#   3. tests/fuzz/run.sh 60: the libFuzzer targets for 60 s in total (./build-fuzz).
# Every part runs even if an earlier one failed; the last lines are a
# one-line summary per part, and the exit code is non-zero if any part failed.
#   bash scripts/test.sh [--no-sanitize] [--no-fuzz] [ctest arguments...]
# (the options skip a part, for quick runs by hand; .ci/run uses none; with
# --no-sanitize, ctest in ./build runs the unit tests too).
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
start=$SECONDS
run_sanitize=1 run_fuzz=1
while [ $# -gt 0 ]; do
  case $1 in
    --no-sanitize) run_sanitize=0; shift ;;
    --no-fuzz) run_fuzz=0; shift ;;
    *) break ;;
  esac
done

bash "$repo/scripts/install-deps.sh" || { echo "test: installing the dependencies failed"; exit 1; }
# The unit tests run in the sanitized build; without it, here.
unit_tests=OFF
[ "$run_sanitize" -eq 1 ] || unit_tests=ON
if ! bash "$repo/scripts/build.sh" -DNBM_BUILD_UNIT_TESTS=$unit_tests; then
  echo "test: build failed"
  exit 1
fi
echo "test: built in $((SECONDS - start)) s"

logs="$repo/build/test-logs"
mkdir -p "$logs"
summaries=()
failed_parts=0

# part <name> <summary regex> <command...>: runs the command (output shown and
# kept in build/test-logs/<name>.log) and records a summary line made of the
# last output line matching the regex.
part() {
  local name=$1 pattern=$2 t0=$SECONDS code line status
  shift 2
  echo "test: ---- $name: $*"
  "$@" 2>&1 | tee "$logs/$name.log"
  code=${PIPESTATUS[0]}
  line=$(grep -E "$pattern" "$logs/$name.log" | tail -n 1)
  if [ "$code" -eq 0 ]; then status=PASS; else status="FAIL (exit $code)"; failed_parts=$((failed_parts + 1)); fi
  summaries+=("$(printf 'test: %-9s %s: %s [%d s]' "$name" "$status" "${line:-no summary line}" $((SECONDS - t0)))")
}

cd "$repo/build"
part ctest 'tests passed' ctest --output-on-failure --no-tests=error -j "$(nproc)" "$@"
cd "$repo"
if [ "$run_sanitize" -eq 1 ]; then
  part sanitize '^sanitize: [0-9]+ passed' bash "$repo/tests/sanitize.sh"
fi
if [ "$run_fuzz" -eq 1 ]; then
  part fuzz '^fuzz: [0-9]+ passed' bash "$repo/tests/fuzz/run.sh" 60
fi

echo "test: ==== summary"
printf '%s\n' "${summaries[@]}"
if [ "$failed_parts" -eq 0 ]; then
  echo "test: all parts passed in $((SECONDS - start)) s"
else
  echo "test: $failed_parts part(s) FAILED (total $((SECONDS - start)) s)"
  exit 1
fi
