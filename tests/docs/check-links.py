#!/usr/bin/python3
"""Keeps the links of the documentation working (ctest: docs-links).

For README.md and every docs/**/*.md page (outside code spans and code blocks):
  - every relative link or image `[text](target)` must point at an existing
    file or folder, and a `#anchor` (on the same page or on another .md page)
    at one of its headings (GitHub's anchors);
  - every repository path written in the text or in code spans, such as
    `edp/restart.edp` or `scripts/figures.sh` (a word starting with edp/, geo/,
    scripts/, plugin/, tests/, bench/, docs/ or .ci/), must exist, relative to
    the repository (a C++ module may be named without its .hpp/.cpp; paths
    with wildcards or placeholders are skipped);
and every page of docs/guide/ but its index must name at least one edp/*.edp
script, each of which must exist.

  usage: check-links.py REPO
Standard library only.
"""
import glob
import os
import re
import sys

PATH_PREFIXES = ("edp", "geo", "scripts", "plugin", "tests", "bench", "docs", ".ci")
# A repository path: one of the prefixes, then path characters; not preceded by
# a path character (so that build/tests/... or ../edp/... are not taken apart).
PATH_RE = re.compile(r"(?<![\w./~$-])((?:%s)/[\w./+-]*)" % "|".join(re.escape(p) for p in PATH_PREFIXES))
LINK_RE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def slug(title):
    """GitHub's anchor of a heading."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", title)  # links: their text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(markdown):
    seen = {}
    result = set()
    fenced = False
    for line in markdown.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            s = slug(m.group(1))
            n = seen.get(s, 0)
            seen[s] = n + 1
            result.add(s if n == 0 else "%s-%d" % (s, n))
    return result


def split_code(markdown):
    """(prose, code): the page's text outside and inside code (spans, blocks)."""
    prose, code = [], []
    fenced = False
    for line in markdown.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced or re.match(r"( {4}|\t)", line) and not re.match(r"\s*([-*+]|\d+\.)\s", line):
            code.append(line)
            continue
        code.extend(re.findall(r"`([^`]+)`", line))
        prose.append(re.sub(r"`[^`]+`", " ", line))
    return "\n".join(prose), "\n".join(code)


def repo_paths(text):
    for m in PATH_RE.finditer(text):
        path = m.group(1).rstrip(".,;:")
        after = text[m.end(1):m.end(1) + 1]
        if after in ("*", "{", "<", "[", "$") or re.search(r"[*{}<>$]|\.\.\.|/[A-Z]+(\.|$)", path):
            continue  # a pattern or a placeholder (docs/NAME.md), not a file
        yield path


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    repo = os.path.abspath(sys.argv[1])
    pages = [os.path.join(repo, "README.md")] + sorted(
        glob.glob(os.path.join(repo, "docs", "**", "*.md"), recursive=True))
    anchor_cache = {}

    def anchors_of(path):
        if path not in anchor_cache:
            anchor_cache[path] = anchors(read(path))
        return anchor_cache[path]

    problems = []
    links = paths = scripts = 0
    for page in pages:
        rel = os.path.relpath(page, repo)
        text = read(page)
        prose, code = split_code(text)
        for target in LINK_RE.findall(prose):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                continue  # http:, https:, mailto:
            links += 1
            path, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not os.path.exists(dest):
                problems.append("%s: link to %s: no such file" % (rel, target))
                continue
            if anchor and dest.endswith(".md") and os.path.isfile(dest):
                if anchor not in anchors_of(dest):
                    problems.append("%s: link to %s: no heading with that anchor in %s"
                                    % (rel, target, os.path.relpath(dest, repo)))
        for path in set(repo_paths(prose)) | set(repo_paths(code)):
            paths += 1
            full = os.path.join(repo, path)
            if not any(os.path.exists(full + ext) for ext in ("", ".hpp", ".cpp")):
                problems.append("%s: names %s, which does not exist" % (rel, path))
        if os.path.dirname(rel) == os.path.join("docs", "guide") and os.path.basename(rel) != "README.md":
            named = set(re.findall(r"(?<![\w/.-])(edp/[\w.+-]+\.edp)\b", text))
            scripts += len(named)
            if not named:
                problems.append("%s: a guide page names no edp/*.edp script to run" % rel)
            for script in sorted(named):
                if not os.path.isfile(os.path.join(repo, script)):
                    problems.append("%s: names %s, which does not exist" % (rel, script))
    problems = list(dict.fromkeys(problems))  # a guide script is also a repository path
    if problems:
        print("docs-links: %d problem(s) in %d pages:" % (len(problems), len(pages)))
        for p in problems:
            print("  " + p)
        return 1
    print("docs-links: %d pages, %d relative links, %d repository paths and %d guide scripts, "
          "all found" % (len(pages), links, paths, scripts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
