# Shell helpers shared by the scripts of scripts/, tests/scripts/ and bench/.
# Source it: . "$repo/scripts/lib.sh"

# summary_value TEXT KEY: the value of the last word `KEY=value` in TEXT (the
# one-line summaries the .edp scripts print, e.g. `errU=0.01 energyFinal=3`);
# empty if there is none. Words are separated by blanks and newlines.
summary_value() {
  printf '%s\n' "$1" | tr -s ' \t' '\n\n' | sed -n "s/^$2=//p" | tail -n 1
}
