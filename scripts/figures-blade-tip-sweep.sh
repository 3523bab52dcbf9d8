#!/usr/bin/env bash
# Regenerates the blade-tip interaction map of docs/results/forced.md from a fresh run of
# edp/blade-tip-sweep.edp (issue 15, item 6):
#   docs/blade-tip-sweep.png  tip displacement and largest contact force of the
#                             forced periodic responses against the rotation
#                             speed (stable solid, unstable dashed), with the
#                             engine-order lines of the blade's axial modes
#   docs/blade-tip-sweep.md   the run's summary, with the settling check at one
#                             point (nbmStep from rest against the orbit)
# Needs a build (scripts/build.sh); intermediate files go to out/figures.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
bash "$repo/scripts/freefem.sh" "$repo/edp/blade-tip-sweep.edp" -out blade-tip-sweep -settle 1 > /dev/null
cp blade-tip-sweep.png "$repo/docs/blade-tip-sweep.png"
md="$repo/docs/blade-tip-sweep.md"
{
  echo "Blade-tip / casing interaction map (edp/blade-tip-sweep.edp, defaults, \`-settle 1\`)."
  echo "Produced by \`bash scripts/figures-blade-tip-sweep.sh\`."
  echo
  echo '```'
  cat blade-tip-sweep-summary.txt
  echo '```'
} > "$md"
cat "$md"
