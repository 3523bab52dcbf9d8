#!/usr/bin/env python3
"""The include graph of the nbm core runs only downwards (docs/layout.md).

    python3 tests/layout/check-include-graph.py [repository-root]

plugin/core is split into folders, one CMake target nbm_<folder> each
(plugin/core/CMakeLists.txt). The layering is read from the CMake files
themselves, and nowhere else: the folders are the add_subdirectory() lines of
plugin/core/CMakeLists.txt, and a folder's target links the layers right
below it (target_link_libraries(nbm_<folder> ... nbm_<below> ...) in
plugin/core/<folder>/CMakeLists.txt). A folder may include from itself and
from every folder its target reaches through those links, nothing else.

Fails (exit 1), naming the file, the line and the include, if
  - a core file includes from a folder its target does not reach (an include
    that runs back up, or sideways to a layer that is not below it);
  - a quoted include does not resolve to an existing file from the single
    include root plugin/core ("linalg/lcp.hpp", not "lcp.hpp" or "../x");
  - a core file includes a FreeFEM header (ff++.hpp, AFunction.hpp, ...) or
    any header that is not the standard library's, Eigen's, CHOLMOD's,
    MUMPS's, MPI's or Spectra's (the core's external dependencies:
    plugin/core/linalg/CMakeLists.txt);
  - the CMake links of the layers form a cycle, a layer links a target that
    is not a layer, a folder of the core has no target of its own, or a
    .cpp of a folder is not compiled by its folder's target.
Prints the layering and the folder-level include graph (counts of #include
lines). Python 3, standard library only, no build needed (ctest -L layout).
"""

import os
import re
import sys

CORE = os.path.join("plugin", "core")
SOURCE_SUFFIXES = (".hpp", ".cpp", ".h", ".cc", ".ipp", ".inl")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]*)[>"]')
# External headers the core may include: the C++ standard library (no
# extension), Eigen, CHOLMOD, MUMPS (double precision, C interface), MPI,
# Spectra (header only). A new dependency is added here and to the CMake
# target that links it.
EXTERNAL = (re.compile(r"^[a-z_]+$"), re.compile(r"^Eigen/[A-Za-z]+$"),
            re.compile(r"^cholmod\.h$"), re.compile(r"^dmumps_c\.h$"), re.compile(r"^mpi\.h$"),
            re.compile(r"^Spectra/(MatOp/)?[A-Za-z]+\.h$"))
# FreeFEM's headers (the binding's, plugin/freefem): named as such when met.
FREEFEM = {"ff++.hpp", "AFunction.hpp", "AFunction_ext.hpp", "AddNewFE.h", "RNM.hpp",
           "fem.hpp", "FESpace.hpp", "FESpacen.hpp", "MatriceCreuse.hpp", "MatriceCreuse_tpl.hpp",
           "lgfem.hpp", "lgmesh3.hpp", "lgsolver.hpp", "Mesh1dn.hpp", "Mesh2dn.hpp",
           "Mesh3dn.hpp", "MeshLn.hpp", "MeshSn.hpp", "msh3.hpp", "ffstack.hpp", "AnyType.hpp",
           "CodeAlloc.hpp", "ffapi.hpp", "PkLagrange.hpp", "Operator.hpp", "problem.hpp",
           "FreeFEM-config.h", "error.hpp"}


def strip_cmake_comments(text):
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def cmake_calls(text, command):
    """Argument lists of every call of `command` (no nested parentheses)."""
    pattern = re.compile(r"\b" + command + r"\s*\(([^)]*)\)", re.IGNORECASE)
    return [m.group(1).split() for m in pattern.finditer(strip_cmake_comments(text))]


def read_layers(core, errors):
    """{folder: set of folders its target links directly}, in CMake order."""
    top = os.path.join(core, "CMakeLists.txt")
    rel = lambda path: os.path.relpath(path, os.path.dirname(os.path.dirname(core)))
    folders = [args[0] for args in cmake_calls(open(top).read(), "add_subdirectory") if args]
    links = {}
    for folder in folders:
        links[folder] = set()
        cmake = os.path.join(core, folder, "CMakeLists.txt")
        if not os.path.isfile(cmake):
            errors.append(f"{rel(top)}: add_subdirectory({folder}) but no {rel(cmake)}")
            continue
        text = open(cmake).read()
        target = "nbm_" + folder
        if not any(args and args[0] == target for args in cmake_calls(text, "add_library")):
            errors.append(f"{rel(cmake)}: does not define the folder's target {target}")
        for args in cmake_calls(text, "target_link_libraries"):
            if not args or args[0] != target:
                continue
            for item in args[1:]:
                if not item.startswith("nbm_"):
                    continue  # keywords, Eigen, CHOLMOD, ...
                below = item[len("nbm_"):]
                if below not in folders:
                    errors.append(f"{rel(cmake)}: {target} links {item}, which is not a layer of "
                                  f"the core (plugin/core/CMakeLists.txt, add_subdirectory)")
                else:
                    links[folder].add(below)
        # every .cpp of the folder is compiled by the folder's target
        listed = set()
        for args in cmake_calls(text, "add_library"):
            if args and args[0] == target:
                listed.update(os.path.basename(a) for a in args[1:])
        for name in sorted(os.listdir(os.path.join(core, folder))):
            if name.endswith((".cpp", ".cc")) and name not in listed:
                errors.append(f"{rel(cmake)}: {folder}/{name} is not a source of {target}")
    return folders, links


def reach(links):
    """{folder: folders reachable through the links}; cycles reported."""
    closure = {}
    for start in links:
        seen, todo = set(), list(links[start])
        while todo:
            f = todo.pop()
            if f not in seen:
                seen.add(f)
                todo.extend(links.get(f, ()))
        closure[start] = seen
    cycles = sorted(f for f in links if f in closure[f])
    return closure, cycles


def layering(folders, links):
    """Folders lowest first: each after everything its target links (CMake order
    among independent ones)."""
    order, placed = [], set()
    while len(order) < len(folders):
        ready = [f for f in folders if f not in placed and links.get(f, set()) <= placed]
        if not ready:  # a cycle, reported apart: the rest in CMake order
            order += [f for f in folders if f not in placed]
            break
        order.append(ready[0])
        placed.add(ready[0])
    return order


def freefem_names():
    names = set(FREEFEM)
    system_dir = "/usr/include/freefem++"
    if os.path.isdir(system_dir):
        names.update(n for n in os.listdir(system_dir) if "." in n)
    return names


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    core = os.path.join(root, CORE)
    errors = []
    folders, links = read_layers(core, errors)
    closure, cycles = reach(links)
    for f in cycles:
        errors.append(f"{CORE}/{f}/CMakeLists.txt: nbm_{f} reaches itself through its links "
                      f"(a cycle of layers: {f} -> {', '.join(sorted(links[f]))})")
    freefem = freefem_names()

    graph = {f: {} for f in folders}
    n_files = n_quoted = 0
    for dirpath, dirnames, filenames in os.walk(core):
        dirnames.sort()
        for name in sorted(filenames):
            if not name.endswith(SOURCE_SUFFIXES):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, root)
            parts = os.path.relpath(path, core).split(os.sep)
            if len(parts) == 1:
                errors.append(f"{rel}: a core file outside every folder (layer)")
                continue
            own = parts[0]
            if own not in links:
                errors.append(f"{rel}: folder {own}/ is no layer of the core (no "
                              f"add_subdirectory({own}) in {CORE}/CMakeLists.txt)")
                continue
            n_files += 1
            with open(path, encoding="utf-8", errors="replace") as handle:
                for number, line in enumerate(handle, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    kind, target = m.group(1), m.group(2).strip()
                    where = f"{rel}:{number}: #include {kind}{target}{'>' if kind == '<' else kind}"
                    base = target.rsplit("/", 1)[-1]
                    if "freefem" in target.lower() or (base in freefem and not (
                            kind == '"' and os.path.isfile(os.path.join(core, target)))):
                        errors.append(f"{where}: a FreeFEM header in the core (the binding, "
                                      f"plugin/freefem, is the only part that includes FreeFEM)")
                        continue
                    if kind == "<":
                        if not any(p.match(target) for p in EXTERNAL):
                            errors.append(f"{where}: not a header of the standard library, "
                                          f"Eigen, CHOLMOD, MUMPS, MPI or Spectra (the core's "
                                          f"dependencies)")
                        continue
                    target_parts = target.split("/")
                    if (target.startswith("/") or ".." in target_parts or len(target_parts) < 2
                            or not os.path.isfile(os.path.join(core, target))):
                        errors.append(f"{where}: does not resolve to a file from the include "
                                      f"root {CORE} (write it as <folder>/<file>)")
                        continue
                    n_quoted += 1
                    to = target_parts[0]
                    graph[own][to] = graph[own].get(to, 0) + 1
                    if to != own and to not in closure.get(own, set()):
                        allowed = ", ".join([own] + [f for f in folders if f in closure[own]])
                        errors.append(f"{where}: {own}/ includes from {to}/, which is not below "
                                      f"it (nbm_{own} does not reach nbm_{to}; {own}/ may "
                                      f"include from {allowed})")

    order = layering(folders, links)
    print(f"Layers of {CORE}, lowest first (from the CMake targets' links):")
    for f in order:
        below = ", ".join(f"nbm_{b}" for b in sorted(links[f], key=order.index)) or "-"
        print(f"  {f:<9} nbm_{f:<9} links {below}")
    print(f"\nFolder include graph ({n_quoted} #include \"...\" lines in {n_files} files; "
          f"folder -> folders it includes from, with the number of lines):")
    for f in order:
        edges = sorted(graph[f].items(), key=lambda e: (order.index(e[0]) if e[0] in order else -1))
        text = ", ".join(f"{to} {count}" for to, count in edges) or "-"
        print(f"  {f:<9} -> {text}")
    if errors:
        print(f"\n{len(errors)} violation(s) of the layering:", file=sys.stderr)
        for e in errors:
            print("  " + e, file=sys.stderr)
        return 1
    print("\nOK: every include of the core resolves from plugin/core and runs down or "
          "within its folder; no FreeFEM header.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
