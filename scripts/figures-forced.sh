#!/usr/bin/env bash
# Regenerates the forced-response figure and numbers of docs/results/forced.md from fresh runs
# of edp/forced-plate.edp (issue 15, item 6):
#   docs/forced-plate.png   amplitude against forcing frequency: the continuation
#                           (stable solid, unstable dashed, events), the sweeps
#                           up and down, the linear response, and the backbone
#                           of the excited mode (edp/forced-plate-backbone.idp)
#   docs/forced-plate.md    the summaries of the run with contact (defaults) and of
#                           the contact-free run against the direct frequency
#                           response (paper NBM, -contactFree 1 -mass consistent)
# Needs a build (scripts/build.sh); intermediate files go to out/figures.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
run() { bash "$repo/scripts/freefem.sh" "$repo/edp/forced-plate.edp" "$@" > /dev/null; }
run -out forced-plate
run -out forced-plate-linear -contactFree 1 -mass consistent -points 31 -down 0 -settle 0
cp forced-plate-curve.png "$repo/docs/forced-plate.png"
md="$repo/docs/forced-plate.md"
{
  echo "Forced clamped plate (edp/forced-plate.edp). Produced by \`bash scripts/figures-forced.sh\`."
  echo
  echo "With the wall (defaults):"
  echo
  echo '```'
  cat forced-plate-summary.txt
  echo '```'
  echo
  echo "Contact-free, paper NBM (\`-contactFree 1 -mass consistent -points 31 -down 0 -settle 0\`):"
  echo
  echo '```'
  cat forced-plate-linear-summary.txt
  echo '```'
} > "$md"
cat "$md"
