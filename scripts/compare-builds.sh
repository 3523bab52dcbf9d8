#!/usr/bin/env bash
# Runs examples with the plugin of an earlier revision and with the current
# build, and compares their outputs byte for byte: a refactoring of the core
# must leave every trajectory as it was (or say where it does not).
#
#   bash scripts/compare-builds.sh REV [--work DIR]
#
# REV is built (plugin and Element_PkL only) in a git worktree under DIR
# (default /tmp/nbm-compare); the current plugin is ./build (scripts/build.sh).
# Each example runs with REV's scripts on REV's plugin and with the current
# scripts on the current plugin (the scripts may change with the API). Per
# example it prints the exit codes, the number of differing stdout lines
# (lines that report times left out) and of differing output files (every
# file but the PNG plots); the last line says how many examples differ.
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
rev=${1:?usage: bash scripts/compare-builds.sh REV [--work DIR]}
work=/tmp/nbm-compare
[ "${2:-}" = "--work" ] && work=${3:?--work needs a folder}
src="$work/src" old_build="$work/build"
mkdir -p "$work"
if [ ! -d "$src" ] || [ "$(git -C "$src" rev-parse HEAD 2>/dev/null)" != "$(git -C "$repo" rev-parse "$rev")" ]; then
  rm -rf "$src"
  git -C "$repo" worktree prune
  git -C "$repo" worktree add -f --detach "$src" "$rev" -q || exit 1
fi
cmake -S "$src" -B "$old_build" -DCMAKE_BUILD_TYPE=Release > /dev/null || exit 1
cmake --build "$old_build" -j "$(nproc)" --target nbm Element_PkL > "$work/build.log" 2>&1 ||
  { tail -20 "$work/build.log"; exit 1; }

# Lines that report wall-clock times differ from run to run.
untimed() { grep -viE "wall|seconds|elapsed|cpu time|[0-9.]+ ?s\b" "$1"; }
differing=0 total=0
compare() {  # compare <name> <script> [args...]
  local name=$1 script=$2 side
  shift 2
  for side in old new; do
    local dir="$work/$side-$name"
    rm -rf "$dir" && mkdir -p "$dir"
    if [ $side = old ]; then
      (cd "$dir" && bash "$src/tests/scripts/run-freefem.sh" "$old_build" "$src" "$src/edp/$script" "$@" > stdout.txt 2>&1)
    else
      (cd "$dir" && bash "$repo/tests/scripts/run-freefem.sh" "$repo/build" "$repo" "$repo/edp/$script" "$@" > stdout.txt 2>&1)
    fi
    echo $? > "$dir/exit-code"
  done
  local old="$work/old-$name" new="$work/new-$name" files n_files=0 n_diff=0 f
  local lines
  lines=$(diff <(untimed "$old/stdout.txt") <(untimed "$new/stdout.txt") | grep -c '^[<>]')
  files=$(cd "$old" && find . -type f ! -name stdout.txt ! -name exit-code ! -name '*.png' | sort)
  for f in $files; do
    n_files=$((n_files + 1))
    cmp -s "$old/$f" "$new/$f" || n_diff=$((n_diff + 1))
  done
  total=$((total + 1))
  local codes="exit $(cat "$old/exit-code") / $(cat "$new/exit-code")"
  if [ "$lines" -ne 0 ] || [ $n_diff -ne 0 ] || [ "$codes" != "exit 0 / 0" ]; then
    differing=$((differing + 1))
  fi
  printf '%-26s %s, stdout lines differing %s, files %s differing %s\n' "$name" "$codes" "$lines" \
    "$n_files" "$n_diff"
}

quiet="-vtkFrames 0 -snapshots 0"
compare plate-consistent bouncing-plate.edp -T 0.3 $quiet
compare plate-redistributed bouncing-plate.edp -T 0.3 -mass redistributed $quiet
compare plate-moreau-jean bouncing-plate.edp -T 0.3 -scheme moreau-jean $quiet
compare plate-explicit bouncing-plate.edp -T 0.3 -scheme explicit -dt 1e-4 $quiet
compare plate-damped bouncing-plate.edp -T 0.3 -rayleigh 2,1e-4 $quiet
compare bar-p2 bouncing-bar.edp -order 2 -N 40
compare disc-bowl disc-bowl.edp
compare cantilever-massless cantilever-plate-periodic.edp -out c -frames 2 -samples 20
compare cantilever-consistent cantilever-plate-periodic.edp -out c -frames 2 -samples 20 \
  -mass consistent -condition displacement -tau 0.3
compare plate-backbone plate-backbone.edp -out b -points 12
compare forced-bar forced-bar.edp -out fb -doubling 1 -doublingAmplitude 0.05
compare forced-plate forced-plate.edp -out fp -points 31 -down 0 -arclength 0
echo "compare-builds: $total examples against $rev, $differing differing"
