#!/usr/bin/env bash
# Runs every command `bash scripts/freefem.sh edp/X.edp ...` of README.md and
# docs/guide/*.md as written (page order, each command once), with the built
# plugin of ./build, and prints one line per command: exit code, seconds, page,
# command. A command the page shows failing on purpose (troubleshooting.md)
# must fail with the message the page quotes; every other one must end with 0.
#   bash tests/docs/run-guide-commands.sh      # about 4 minutes on 2 cores
# The commands run from a scratch folder that links edp/, geo/, scripts/,
# tests/ and build/ of the repository, so that their output files (VTK
# series, plots, CSV) land there and not in the repository; it is removed at
# the end unless KEEP=1. Not a ctest test (too long for every run); the last
# line is "guide: N commands, M failed".
# (docs-commands, tests/docs/check-commands.py, checks on every run that these
# commands name existing scripts and options.)
set -u
repo=$(cd "$(dirname "$0")/../.." && pwd)
[ -e "$repo/build/plugin/nbm.so" ] || { echo "guide: build the plugin first (bash scripts/build.sh)"; exit 1; }
work=$(mktemp -d)
for d in edp geo scripts tests build; do ln -s "$repo/$d" "$work/$d"; done
cp "$repo/README.md" "$work/"
mkdir -p "$work/docs" && ln -s "$repo/docs/guide" "$work/docs/guide"
cd "$work" || exit 1

# The failing example of troubleshooting.md: its command and the message it quotes.
expected_failure='edp/bouncing-plate.edp -scheme explicit -dt 1e-2'
expected_message='dt: 0.01 exceeds the critical time step'

mapfile -t lines < <(/usr/bin/python3 - <<'EOF'
import glob, re
seen = []
for page in ["README.md"] + sorted(glob.glob("docs/guide/*.md")):
    for line in open(page, encoding="utf-8"):
        for m in re.finditer(r"(bash scripts/freefem\.sh edp/[\w./-]+\.edp[^`#\n|]*)", line):
            command = m.group(1).strip()
            if "X.edp" not in command and command not in [c for _, c in seen]:
                seen.append((page, command))
for page, command in seen:
    print(page + "\t" + command)
EOF
)
failed=0
for entry in "${lines[@]}"; do
  page=${entry%%$'\t'*} command=${entry#*$'\t'}
  start=$SECONDS
  bash -c "$command" >"$work/log.txt" 2>&1
  code=$?
  status=ok
  if [[ $command == *"$expected_failure"* ]]; then
    if [ "$code" -eq 0 ] || ! grep -q "$expected_message" "$work/log.txt"; then status=FAILED; fi
  elif [ "$code" -ne 0 ]; then
    status=FAILED
  fi
  if [ "$status" = FAILED ]; then
    failed=$((failed + 1))
    tail -n 5 "$work/log.txt"
  fi
  printf 'guide: %-6s exit %d, %4d s  %s  %s\n' "$status" "$code" $((SECONDS - start)) "$page" "$command"
done
cd "$repo" || exit 1
[ "${KEEP:-0}" = 1 ] && echo "guide: outputs kept in $work" || rm -rf "$work"
echo "guide: ${#lines[@]} commands, $failed failed"
[ "$failed" -eq 0 ]
