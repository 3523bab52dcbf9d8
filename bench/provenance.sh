# Sourced by the bench scripts that write a results page.
#
# provenance <paths...> prints "<short commit>" and, if the given paths have
# uncommitted changes, " with uncommitted changes to <paths>", so that a page
# says which code it measured.
provenance() {
  local repo dirty=""
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  [ -z "$(git -C "$repo" status --porcelain -- "$@")" ] || dirty=" with uncommitted changes to $*"
  printf '%s%s' "$(git -C "$repo" rev-parse --short HEAD)" "$dirty"
}

# bench_tool <name>: the path of build/bench/<name>, or a message and exit 1
# if it is not built.
bench_tool() {
  local repo tool
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  tool="$repo/build/bench/$1"
  [ -x "$tool" ] || { echo "$1: build first (bash scripts/build.sh)" >&2; exit 1; }
  printf '%s' "$tool"
}

# tool_blocks <tool> <arguments>...: for each argument string, a fenced block
# with the command line and what the tool printed.
tool_blocks() {
  local tool=$1 args
  shift
  for args in "$@"; do
    echo '```'
    echo "\$ $(basename "$tool") $args"
    # shellcheck disable=SC2086
    "$tool" $args
    echo '```'
    echo
  done
}

# write_page <page> <function>: runs <function>, which prints the page's
# Markdown, and moves what it printed to <page> (mode 644) once it is done,
# then prints it. The function may use "$work", a scratch folder removed
# afterwards.
write_page() {
  local page=$1 tmp
  tmp=$(mktemp)
  work=$(mktemp -d)
  "$2" > "$tmp"
  rm -rf "$work"
  chmod 644 "$tmp"
  mv "$tmp" "$page"
  cat "$page"
}
