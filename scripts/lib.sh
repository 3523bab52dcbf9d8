# Shell helpers shared by the scripts of scripts/, tests/scripts/ and bench/.
# Source it: . "$repo/scripts/lib.sh"

# summary_value TEXT KEY: the value of the last word `KEY=value` in TEXT (the
# one-line summaries the .edp scripts print, e.g. `errU=0.01 energyFinal=3`);
# empty if there is none. Words are separated by blanks and newlines.
summary_value() {
  printf '%s\n' "$1" | tr -s ' \t' '\n\n' | sed -n "s/^$2=//p" | tail -n 1
}

# enter_sweep BUILD OUT: for the sweeps (compare-bars, compare-plate,
# drop-3d-scale): installs what is missing and builds when BUILD is 1 (their
# -skip-build makes it 0), sets NBM_BUILD (default $repo/build), creates OUT
# and enters it, leaving its absolute path in `out`.
enter_sweep() {
  if [ "$1" = 1 ]; then
    bash "$repo/scripts/install-deps.sh" >/dev/null
    bash "$repo/scripts/build.sh" >/dev/null
  fi
  NBM_BUILD=${NBM_BUILD:-$repo/build}
  mkdir -p "$2"
  out=$(cd "$2" && pwd)
  cd "$out"
}

# plot_contact_end PNG TITLE CURVES: the paper-Figure-1 style plot of the
# bouncing bar's contact-end height u(0,t) (bouncing-bar.edp CSVs: t, u(0,t),
# exact) with a zoom on the first contact, flight and second contact. CURVES:
# gnuplot plot items, the exact solution first.
plot_contact_end() {
  gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1100,800 font ',11'
set output '$1'
set multiplot layout 2,1 title '$2'
set xlabel 't'; set ylabel 'u(0,t)'; set grid; set autoscale xfix
set key outside top center horizontal
curves = "$3"
plot @curves
set title 'zoom: first contact, flight with the bar vibrating, second contact'
set xrange [0.8:4.6]; set yrange [-0.2:4.8]
unset key
plot @curves
unset multiplot
GP
}
