#!/usr/bin/env bash
# Regenerates the forced-bar figure and numbers of docs/results/forced.md from fresh runs of
# edp/forced-bar.edp (issue 15, item 6):
#   docs/forced-bar.png   amplitude of the contact end against the forcing
#                         frequency: the continuation (stable solid, unstable
#                         dashed, events), the period-2 branch switched to at
#                         the first period doubling, the linear responses (FE
#                         direct solve, continuous bar)
#   docs/forced-bar.md    the summary of that run, and the FE response without
#                         contact against the continuous bar's on refined
#                         meshes (the wall out of reach, -gap 10)
# Needs a build (scripts/build.sh); intermediate files go to out/figures.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
run() { bash "$repo/scripts/freefem.sh" "$repo/edp/forced-bar.edp" "$@"; }
run -out forced-bar -doubling 1 -doublingAmplitude 0.05 > /dev/null
cp forced-bar.png "$repo/docs/forced-bar.png"
md="$repo/docs/forced-bar.md"
{
  echo "Forced bar against a wall (edp/forced-bar.edp). Produced by \`bash scripts/figures-forced-bar.sh\`."
  echo
  echo "Defaults with branch switching (\`-doubling 1 -doublingAmplitude 0.05\`):"
  echo
  echo '```'
  cat forced-bar-summary.txt
  echo '```'
  echo
  echo "Without contact (\`-gap 10\`, Rayleigh \`-aM 0.04 -bK 0.004\`): the largest relative"
  echo "difference of |u(0)| between the FE direct response and the continuous bar's over"
  echo "omega / w1 in [0.9, 1.2] (the orbits equal the direct response to the last column):"
  echo
  echo "| element | N | mass | FE / continuous | orbits / direct FE |"
  echo "|---|---|---|---|---|"
  for case in "1 20" "1 40" "1 80" "2 10" "2 20"; do
    set -- $case
    for mass in consistent redistributed; do
      line=$(run -out forced-bar-mesh -order "$1" -N "$2" -mass "$mass" -gap 10 -aM 0.04 \
        -bK 0.004 -checks 3 | grep '^forced-bar:')
      echo "| P$1 | $2 | $mass | $(summary_value "$line" analyticDifference) |" \
        "$(summary_value "$line" linearDifference) |"
    done
  done
} > "$md"
cat "$md"
