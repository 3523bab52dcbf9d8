# Sourced by the bench scripts that write a results page: provenance <paths...>
# prints "<short commit>" and, if the given paths have uncommitted changes,
# " with uncommitted changes to <paths>", so that a page says which code it
# measured.
provenance() {
  local repo dirty=""
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  [ -z "$(git -C "$repo" status --porcelain -- "$@")" ] || dirty=" with uncommitted changes to $*"
  printf '%s%s' "$(git -C "$repo" rev-parse --short HEAD)" "$dirty"
}
