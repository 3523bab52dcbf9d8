#!/usr/bin/python3
"""Keeps docs/reference.md complete (ctest: docs-reference).

Extracts from the sources the names a user can write in a FreeFEM script:
  - plugin/freefem/*.cpp: the functions (Global.Add), the types (zzzfff->Add),
    the finite elements (AddNewFE, AddNewFEL) and the named options of every
    call (the name_param arrays, attached to the call or type that uses them);
  - edp/*.idp: every macro and func, and the global settings of nbm.idp;
and fails, listing them, if any is missing from the reference:
  - a function, type, element or helper must appear in code (a `code span`
    or a code block) as a whole word;
  - a named option must appear as a code span starting with its name
    (`dt`, `dt = ...`) in the section of its call: the text under a heading
    that names the call in code, down to the next heading of the same or a
    higher level.

  usage: check-reference.py REPO [REFERENCE_MD]
(REFERENCE_MD defaults to REPO/docs/reference.md; give another file to try
the check on a modified copy.) Standard library only.
"""
import glob
import os
import re
import sys


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def strip_cpp_comments(text):
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def plugin_names(repo):
    """(functions, types, elements, options) registered by the binding;
    options maps a call or type name to its named options."""
    functions, types, elements = set(), set(), set()
    params = {}  # class name -> [option names]
    registrations = []  # (call or type name, class name)
    sources = sorted(glob.glob(os.path.join(repo, "plugin", "freefem", "*.cpp")))
    if not sources:
        raise SystemExit("check-reference: no plugin/freefem/*.cpp under " + repo)
    for path in sources:
        text = strip_cpp_comments(read(path))
        # Object-like macros (a list of named options shared by two calls):
        # expanded in the name_param arrays below.
        macros = {m.group(1): m.group(2).replace("\\\n", " ")
                  for m in re.finditer(r"#define\s+(\w+)[ \t]+((?:[^\n]*\\\n)*[^\n]*)", text)}
        for m in re.finditer(r"(\w+)\s*(?:<[^>]*>)?\s*::\s*name_param\s*\[\s*\]\s*=\s*\{(.*?)\};",
                             text, re.S):
            body = re.sub(r"\b(\w+)\b", lambda t: macros.get(t.group(1), t.group(1)), m.group(2))
            params.setdefault(m.group(1), []).extend(
                re.findall(r'\{\s*"(\w+)"\s*,\s*&typeid', body))
        last_type = None
        events = []
        for m in re.finditer(r'Global\.Add\(\s*"(\w+)"\s*,\s*"\("\s*,\s*new\s+([^;]*);', text):
            events.append((m.start(), "function", m.group(1), m.group(2)))
        for m in re.finditer(r'zzzfff->Add\(\s*"(\w+)"', text):
            events.append((m.start(), "type", m.group(1), None))
        for m in re.finditer(r'TheOperators->Add\(\s*"<-"\s*,\s*new\s+([^;]*);', text):
            events.append((m.start(), "constructor", None, m.group(1)))
        for m in re.finditer(r'AddNewFEL?\(\s*"(\w+)"', text):
            elements.add(m.group(1))
        for _, kind, name, op in sorted(events):
            if kind == "type":
                types.add(name)
                last_type = name
                continue
            if kind == "function":
                functions.add(name)
            elif last_type is None:
                continue  # an operator that constructs no type of this file
            else:
                name = last_type
            # new XOp(...) -> X; new ForcedOp<ForcedOrbit<A>, ...> -> ForcedOrbit
            m = re.match(r"\s*\w+\s*<\s*(\w+)", op)
            cls = m.group(1) if m else re.sub(r"Op$", "", re.match(r"\s*(\w+)", op).group(1))
            registrations.append((name, cls))
    options = {}
    attached = set()
    for name, cls in registrations:
        if cls in params:
            options.setdefault(name, set()).update(params[cls])
            attached.add(cls)
    unattached = sorted(set(params) - attached)
    return functions, types, elements, options, unattached


def idp_names(repo):
    """Macros and funcs of edp/*.idp, and the global settings of nbm.idp."""
    names = {}
    paths = sorted(glob.glob(os.path.join(repo, "edp", "*.idp")))
    if not paths:
        raise SystemExit("check-reference: no edp/*.idp under " + repo)
    for path in paths:
        base = os.path.basename(path)
        for line in read(path).split("\n"):
            m = re.match(r"\s*macro\s+(\w+)", line)
            if not m:
                m = re.match(r"\s*func\s+[\w\[\],\s]*?\s(\w+)\s*\(", line)
            if m:
                names.setdefault(m.group(1), base)
            if base == "nbm.idp":
                m = re.match(r"(?:real|int|string|bool)\s+(.*);", line)
                if m:  # top-level declarations: the settings a script may change
                    for part in m.group(1).split(","):
                        ident = re.match(r"\s*(\w+)", part)
                        if ident:
                            names.setdefault(ident.group(1), base)
    return names


def code_text(markdown):
    """The text of the code spans and code blocks of a markdown page."""
    out = []
    fenced = False
    for line in markdown.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced or line.startswith("    "):
            out.append(line)
            continue
        out.extend(re.findall(r"`([^`]+)`", line))
    return "\n".join(out)


def sections(markdown):
    """[(heading text, level, body)]: each heading's text down to the next
    heading of the same or a higher level (outside code blocks)."""
    lines = markdown.split("\n")
    heads = []
    fenced = False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        m = None if fenced else re.match(r"(#{1,6})\s+(.*)", line)
        if m:
            heads.append((i, len(m.group(1)), m.group(2)))
    result = []
    for k, (i, level, title) in enumerate(heads):
        end = len(lines)
        for j, lev, _ in heads[k + 1:]:
            if lev <= level:
                end = j
                break
        result.append((title, level, "\n".join(lines[i + 1:end])))
    return result


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        return 2
    repo = sys.argv[1]
    ref_path = sys.argv[2] if len(sys.argv) == 3 else os.path.join(repo, "docs", "reference.md")
    reference = read(ref_path)
    code = code_text(reference)
    functions, types, elements, options, unattached = plugin_names(repo)
    helpers = idp_names(repo)

    missing = []

    def named(word):
        return re.search(r"(?<![\w.])" + re.escape(word) + r"\b", code) is not None

    for kind, names in (("type", types), ("function", functions), ("finite element", elements)):
        missing += ["%s %s (plugin/freefem)" % (kind, n) for n in sorted(names) if not named(n)]
    missing += ["helper %s (edp/%s)" % (n, f) for n, f in sorted(helpers.items()) if not named(n)]
    for call, opts in sorted(options.items()):
        texts = [body for title, _, body in sections(reference)
                 if re.search(r"`[^`]*\b" + re.escape(call) + r"\b[^`]*`", title)]
        if not texts:
            missing.append("section: no heading names `%s` (its named options: %s)"
                           % (call, ", ".join(sorted(opts))))
            continue
        text = "\n".join(texts)
        for opt in sorted(opts):
            if not re.search(r"`" + re.escape(opt) + r"\b", text):
                missing.append("named option %s of %s" % (opt, call))
    for cls in unattached:
        missing.append("the named options of class %s belong to no registered call "
                       "(update tests/docs/check-reference.py)" % cls)

    total = len(types) + len(functions) + len(elements) + len(helpers) + sum(
        len(o) for o in options.values())
    if missing:
        print("docs-reference: %s lacks %d of the %d names the sources define:"
              % (ref_path, len(missing), total))
        for m in missing:
            print("  missing: " + m)
        return 1
    print("docs-reference: %s names all %d: %d types, %d functions, %d finite elements, "
          "%d named options of %d calls, %d helpers of edp/*.idp"
          % (ref_path, total, len(types), len(functions), len(elements),
             sum(len(o) for o in options.values()), len(options), len(helpers)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
