#!/usr/bin/env bash
# Regenerates the 3D blade figures and numbers of docs/results/forced.md ("A 3D blade against
# an ovalised casing") from a fresh run of edp/forced-blade-3d.edp at its defaults (about 2.2e4
# dofs on geo/blade.geo, 20 modes):
#   docs/forced-blade-3d.png        the response curve with stability and events, the backbone
#   docs/forced-blade-3d-orbit.png  the largest-amplitude orbit's tip against the casing
#   docs/forced-blade-3d.md         the run's summary, its modes-convergence table, wall time
# The VTK snapshots of that orbit stay in out/figures (forced-blade-3d-orbit.pvd).
# Needs a build (scripts/build.sh); one BLAS thread (the reduced model's matrices are small).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
export OPENBLAS_NUM_THREADS=1
start=$(date +%s)
line=$(bash "$repo/scripts/freefem.sh" "$repo/edp/forced-blade-3d.edp" -out forced-blade-3d | tail -n 1)
seconds=$(( $(date +%s) - start ))
cp forced-blade-3d.png "$repo/docs/forced-blade-3d.png"
cp forced-blade-3d-orbit.png "$repo/docs/forced-blade-3d-orbit.png"
md="$repo/docs/forced-blade-3d.md"
{
  echo "3D blade against an ovalised casing (edp/forced-blade-3d.edp, defaults). Produced by"
  echo "\`bash scripts/figures-blade.sh\` in ${seconds} s of wall time on $(nproc) cores."
  echo
  echo '```'
  cat forced-blade-3d-summary.txt
  echo '```'
  echo
  echo "The clamped blade's lowest modes (full model):"
  echo
  echo '```'
  cat forced-blade-3d-modes.txt
  echo '```'
  echo
  echo "Summary line:"
  echo
  echo '```'
  echo "$line"
  echo '```'
} > "$md"
cat "$md"
