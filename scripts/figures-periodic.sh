#!/usr/bin/env bash
# Regenerates the periodic-solution figures and numbers of docs/results/periodic.md from fresh
# runs of edp/cantilever-plate-periodic.edp (paper Figure 3):
#   docs/cantilever-periodic.png          |u| over one period (massless boundary)
#   docs/cantilever-periodic-probe.png    probe motion and smallest gap over one period
#   docs/cantilever-periodic-family.png   period against energy along the orbit's family
#   docs/cantilever-periodic.md           summary of both mass treatments and the
#                                         harmonic-balance / shooting agreement against H
#   docs/plate-backbone.png               backbone of the first mode from grazing
#                                         (edp/plate-backbone.edp, defaults)
# Needs a build (scripts/build.sh); intermediate files go to out/figures.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/lib.sh"
work="$repo/out/figures"
mkdir -p "$work" "$repo/docs"
cd "$work"
run() { bash "$repo/scripts/freefem.sh" "$repo/edp/cantilever-plate-periodic.edp" "$@" | tail -n 1; }

md="$repo/docs/cantilever-periodic.md"
{
  echo "Clamped plate in contact (edp/cantilever-plate-periodic.edp, defaults: 26 P1 triangles, E = 1000,"
  echo "nu = 0.3, gap 0.01, bar guess tau = 0.2). Produced by \`bash scripts/figures-periodic.sh\`."
  echo
  echo "| mass | H | period (shooting) | period (harmonic balance) | rel. difference | periodicity res. | complementarity res. | switches | contact time / T | max abs(multiplier) | drift 10 T (exact flow) | drift 10 T (Newmark, T/400) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$md"
row() {  # row <mass label> <H> <output line>
  local o=$3
  echo "| $1 | $2 | $(summary_value "$o" Tshooting) | $(summary_value "$o" Thb) | $(summary_value "$o" periodDifference) | $(summary_value "$o" periodicity) | $(summary_value "$o" complementarity) | $(summary_value "$o" switches) | $(awk -v a="$(summary_value "$o" contactTime)" -v b="$(summary_value "$o" Tshooting)" 'BEGIN { printf "%.3f", a / b }') | $(summary_value "$o" maxMultiplier) | $(summary_value "$o" driftExact) | $(summary_value "$o" driftNewmark) |" >> "$md"
}
for H in 20 40 80 160; do
  out=$(run -harmonics $H -out cantilever-H$H)
  row "redistributed" $H "$out"
done
cp cantilever-H40-snapshots.png "$repo/docs/cantilever-periodic.png"
cp cantilever-H40-probe.png "$repo/docs/cantilever-periodic-probe.png"
cp cantilever-H40-family.png "$repo/docs/cantilever-periodic-family.png"
for H in 40 160; do
  out=$(run -harmonics $H -mass consistent -condition displacement -tau 0.3 -out cantilever-consistent-H$H)
  row "consistent (tau 0.3)" $H "$out"
done
cat "$md"
bash "$repo/scripts/freefem.sh" "$repo/edp/plate-backbone.edp" | tail -n 1
cp plate-backbone.png "$repo/docs/plate-backbone.png"
