#!/usr/bin/python3
"""Keeps the commands of the documentation runnable as written (ctest: docs-commands).

For README.md and every docs/**/*.md page, every command
    bash scripts/freefem.sh edp/X.edp -name value ...
(in code blocks and code spans, with or without a leading `$ `) must name an
existing script, and every option `-name` it passes must be one the script
reads: a getARGV("-name", ...) of the script or of a file it includes
(`include "Y.idp"`, searched next to it, recursively). A renamed or removed
option would otherwise be ignored silently by getARGV, and the page would run
the defaults while claiming something else. Commands `bash scripts/X.sh` and
`bash bench/X.sh` must name existing files.

What this does not check: that the runs end well (the script tests of
tests/scripts run every example, most with the options the guide shows).

  usage: check-commands.py REPO
Standard library only.
"""
import glob
import os
import re
import sys

FREEFEM_RE = re.compile(r"bash scripts/freefem\.sh (\S+\.edp)([^`#\n]*)")
SHELL_RE = re.compile(r"bash ((?:scripts|bench)/[\w./-]+\.sh)")
GETARGV_RE = re.compile(r'getARGV\(\s*"(-[^"]+)"')
INCLUDE_RE = re.compile(r'^\s*include\s+"([^"]+)"', re.M)
# Placeholders of the text: a one-letter script name or one outside edp/.
PLACEHOLDER_RE = re.compile(r"(^|/)[A-Z]\.edp$|^(?!edp/)")
# An option: a dash and a letter (a negative number is a value).
OPTION_RE = re.compile(r"^-[A-Za-z]")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def options_of(script, seen=None):
    """The getARGV options of a script and of the files it includes."""
    seen = set() if seen is None else seen
    if script in seen or not os.path.isfile(script):
        return set()
    seen.add(script)
    text = read(script)
    found = set(GETARGV_RE.findall(text))
    for inc in INCLUDE_RE.findall(text):
        found |= options_of(os.path.join(os.path.dirname(script), inc), seen)
    return found


def main(repo):
    pages = [os.path.join(repo, "README.md")] + sorted(
        glob.glob(os.path.join(repo, "docs", "**", "*.md"), recursive=True))
    errors, commands = [], 0
    for page in pages:
        rel = os.path.relpath(page, repo)
        for number, line in enumerate(read(page).splitlines(), 1):
            for script, args in FREEFEM_RE.findall(line):
                if PLACEHOLDER_RE.search(script):
                    continue  # edp/X.edp, script.edp: a pattern, not a command
                commands += 1
                path = os.path.join(repo, script)
                if not os.path.isfile(path):
                    errors.append(f"{rel}:{number}: {script} does not exist")
                    continue
                known = options_of(path)
                for token in args.split():
                    if OPTION_RE.match(token) and token not in known:
                        errors.append(f"{rel}:{number}: {script} reads no option {token} "
                                      f"(it reads: {' '.join(sorted(known)) or 'none'})")
            for shell in SHELL_RE.findall(line):
                commands += 1
                if not os.path.isfile(os.path.join(repo, shell)):
                    errors.append(f"{rel}:{number}: {shell} does not exist")
    for e in errors:
        print("FAIL:", e)
    print(f"docs-commands: {commands} commands on {len(pages)} pages, {len(errors)} problem(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
