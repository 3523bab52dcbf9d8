#!/usr/bin/env bash
# Line coverage of the nbm core (plugin/core/<folder>/*.cpp, every layer) by
# the unit tests (nbm_unit_tests, nbm_periodic_tests), with plain gcov
# (gcovr is not needed).
#
#   tests/unit/coverage.sh [build-dir]     default build dir: <repo>/build-coverage
#
# Configures the build dir with -DNBM_COVERAGE=ON -DCMAKE_BUILD_TYPE=Debug,
# builds and runs the unit tests from zeroed counters, then prints per-file
# and total line coverage. Set NBM_COVERAGE_MISSED=1 to also list the lines
# that were never executed. Exits non-zero if a unit test failed.
set -euo pipefail

src=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$src/build-coverage}
# The objects of plugin/core/<folder>/x.cpp: <objdir>/<folder>/CMakeFiles/nbm_<folder>.dir/x.cpp.o
objdir="$build/plugin/core"

cmake -S "$src" -B "$build" -DNBM_COVERAGE=ON -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build "$build" -j"$(nproc)" --target nbm_unit_tests nbm_periodic_tests >/dev/null

find "$build" -name '*.gcda' -delete
status=0
for t in unit/nbm_unit_tests periodic/nbm_periodic_tests; do
  "$build/tests/$t" --gtest_brief=1 >"$build/$(basename $t).log" 2>&1 || status=$?
  tail -n 2 "$build/$(basename $t).log"
done

# gcov -t prints the annotated sources (the .cpp and every header it pulled
# in) to stdout: "count:line:text", with ##### or ===== for lines never run
# and - for lines without code. Only the blocks of the core's .cpp files count.
for f in "$src"/plugin/core/*/*.cpp; do
  rel=${f#"$src"/plugin/core/}
  folder=$(dirname "$rel")
  (cd "$objdir/$folder/CMakeFiles/nbm_$folder.dir" && gcov -t "$(basename "$f").o" 2>/dev/null)
done | awk -v core="$src/plugin/core/" -v show_missed="${NBM_COVERAGE_MISSED:-0}" '
  /^ *-: *0:Source:/ {
    sub(/^ *-: *0:Source:/, "")
    file = $0
    keep = (index(file, core) == 1 && file ~ /\.cpp$/)
    name = substr(file, length(core) + 1)
    if (keep && !(name in lines)) { order[++n] = name; lines[name] = 0; hit[name] = 0 }
    next
  }
  !keep { next }
  {
    split($0, part, ":")
    count = part[1]; gsub(/ /, "", count)
    if (count == "-") next
    lines[name]++
    if (count ~ /^[0-9]+\*?$/) hit[name]++
    else if (show_missed == "1") { line = part[2]; gsub(/ /, "", line); print "  missed " name ":" line }
  }
  END {
    printf "%-40s %8s %8s %8s\n", "file (plugin/core)", "lines", "run", "cover"
    for (i = 1; i <= n; ++i) {
      f = order[i]; total += lines[f]; run += hit[f]
      printf "%-40s %8d %8d %7.1f%%\n", f, lines[f], hit[f], 100 * hit[f] / lines[f]
    }
    printf "%-40s %8d %8d %7.1f%%\n", "TOTAL", total, run, 100 * run / total
  }'
exit "$status"
