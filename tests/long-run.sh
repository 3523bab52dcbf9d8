#!/usr/bin/env bash
# Long runs through the plugin (tests/scripts/long-run.edp): the bouncing bar
# (edp/bouncing-bar.edp's P1 bar, N = 40) and the bouncing plate
# (plate-setup.idp's defaults), checking at every step a finite state and
# impenetrability, the energy against its initial value E0 where a bound is
# claimed, and the resident memory of FreeFem++ (VmRSS, 100 samples): less
# than 1% growth over the second half of each run (the growth from the first
# tenth, when bounded caches fill, is reported).
#   bash tests/long-run.sh           # shortened: 10^5 bar steps, 10^4 plate steps
#                                    # (about 30 s; the test command's script.long-run)
#   bash tests/long-run.sh --full    # 10^6 bar steps, 10^5 plate steps (about 3 min)
#   options: --build <dir> (default ./build, built by scripts/build.sh)
# Runs and what is checked:
#   bar   mass=redistributed, dt = h/(4c)   E <= E0 + 1e-3 m g h0
#   bar   moreau-jean, e = 1, dt = h/c      E <= E0 + 1e-6 m g h0 (penetration not checked)
#   bar   paper NBM (consistent), dt = h/c  E <= E0 + 1e-3 m g h0 (its energy-stable step,
#         method.md §5.3; without it the paper's step gains energy at lift-offs,
#         tests/periodic/test_bouncing_bar_energy.cpp)
#   plate mass=redistributed                E <= E0 + 1e-3 m g h0
#   plate paper NBM (consistent)            E <= E0 + 1e-3 m g h0
# The last line is "long-run: N passed, M failed".
set -u
repo=$(cd "$(dirname "$0")/.." && pwd)
build="$repo/build"
bar_steps=100000 plate_steps=10000
while [ $# -gt 0 ]; do
  case $1 in
    --full) bar_steps=1000000 plate_steps=100000; shift ;;
    --build) build=$2; shift 2 ;;
    *) echo "usage: bash tests/long-run.sh [--full] [--build <dir>]"; exit 2 ;;
  esac
done
work="$build/long-run"
mkdir -p "$work"
cd "$work"
passed=0 failed=0
run() {  # run <label> <long-run.edp args...>
  local label=$1 t0=$SECONDS out code
  shift
  out=$(bash "$repo/tests/scripts/run-freefem.sh" "$build" "$repo" "$repo/tests/scripts/long-run.edp" \
          -vtkFrames 0 -out "lr-$label" "$@" 2>&1)
  code=$?
  printf '%s\n' "$out" | grep -E '^(long-run:|FAIL)' | sed "s/^/[$label] /"
  if [ $code -eq 0 ] && printf '%s\n' "$out" | grep -q '^long-run:'; then
    passed=$((passed + 1))
  else
    printf '%s\n' "$out" | tail -n 5
    echo "[$label] FAILED (exit code $code, $((SECONDS - t0)) s)"
    failed=$((failed + 1))
  fi
}
run bar-redistributed -body bar -steps $bar_steps -mass redistributed -dtFactor 0.25 -energyTol 1e-3
run bar-moreau-jean -body bar -steps $bar_steps -scheme moreau-jean -restitution 1 -energyTol 1e-6
run bar-paper -body bar -steps $bar_steps -energyTol 1e-3
run plate-redistributed -body plate -steps $plate_steps -mass redistributed -energyTol 1e-3
run plate-paper -body plate -steps $plate_steps -energyTol 1e-3
echo "long-run: $passed passed, $failed failed"
[ $failed -eq 0 ]
