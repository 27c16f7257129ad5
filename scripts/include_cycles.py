#!/usr/bin/env python3
"""Finds include cycles between the project's own files, inside each library.

A component is a header and the sources of the same name in one library (a folder with its own
CMakeLists.txt): scene.h, scene.cpp and include/kdray/scene.h are one component. Component A
uses component B when a file of A includes a header of B. A cycle of uses (A uses B, B uses A,
directly or through others) means neither can be understood, tested or moved without the
other, even where include guards let every file compile; this script lists every such cycle.
A cycle of plain header includes is one too. Includes that resolve to no file of the project
(system and third-party headers, generated files) are not followed.

Usage: include_cycles.py [ROOT]   (ROOT defaults to the repository this script is in)
Exit status 0 when there is no cycle, 1 when there is one (each printed as a chain of includes).
"""

import os
import re
import sys

SOURCE_EXTENSIONS = (".h", ".hpp", ".inc", ".c", ".cc", ".cpp", ".cl")
SKIPPED_FOLDERS = {".git", "build"}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.MULTILINE)


def project_files(root):
    """Every source file under root, as paths relative to it."""
    files = []
    for folder, subfolders, names in os.walk(root):
        subfolders[:] = sorted(d for d in subfolders if d not in SKIPPED_FOLDERS and not d.startswith("build"))
        for name in sorted(names):
            if name.endswith(SOURCE_EXTENSIONS):
                files.append(os.path.relpath(os.path.join(folder, name), root))
    return files


def library_of(root, path):
    """The nearest folder above path with a CMakeLists.txt (a library, a tool, a test suite)."""
    folder = os.path.dirname(path)
    while folder and not os.path.isfile(os.path.join(root, folder, "CMakeLists.txt")):
        folder = os.path.dirname(folder)
    return folder


def component_of(root, path):
    stem = os.path.basename(path).split(".")[0]
    return "%s:%s" % (library_of(root, path) or ".", stem)


def include_roots(files):
    """Where an angle-bracket include is looked up: the root and every include/ folder."""
    roots = {""}
    for path in files:
        parts = path.split(os.sep)
        for i, part in enumerate(parts[:-1]):
            if part == "include":
                roots.add(os.path.join(*parts[: i + 1]))
    return sorted(roots)


def resolve(path, kind, name, known, roots):
    """The project file an include names, or None."""
    candidates = [os.path.join(os.path.dirname(path), name)] if kind == '"' else []
    candidates += [os.path.join(r, name) for r in roots]
    for candidate in candidates:
        candidate = os.path.normpath(candidate)
        if candidate in known:
            return candidate
    return None


def include_graph(root):
    """{file: [(included file, line number)]} over the project's own files."""
    files = project_files(root)
    known = set(files)
    roots = include_roots(files)
    graph = {}
    for path in files:
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
            text = f.read()
        edges = []
        for match in INCLUDE.finditer(text):
            target = resolve(path, match.group(1), match.group(2), known, roots)
            if target is not None and target != path:
                edges.append((target, text.count("\n", 0, match.start()) + 1))
        graph[path] = edges
    return graph


def strongly_connected(nodes, successors):
    """Tarjan's strongly connected components of size > 1, each a sorted list."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(successors(start)))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(successors(child))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                members = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    members.append(member)
                    if member == node:
                        break
                if len(members) > 1:
                    found.append(sorted(members))
    return found


def find_cycles(root):
    """One description per cycle: the components in it and one chain of includes around it."""
    graph = include_graph(root)
    uses = {}  # component -> {used component: (file, included file, line)}
    for path, edges in graph.items():
        source = component_of(root, path)
        for target, line in edges:
            used = component_of(root, target)
            if used != source:
                uses.setdefault(source, {}).setdefault(used, (path, target, line))
    components = sorted(set(component_of(root, p) for p in graph))
    cycles = []
    for members in strongly_connected(components, lambda c: sorted(uses.get(c, {}))):
        inside = set(members)
        # A shortest way round, by breadth-first search inside the cycle from its first member.
        first = members[0]
        previous = {first: None}
        queue, last = [first], None
        while last is None:
            following = []
            for c in queue:
                if first in uses.get(c, {}):
                    last = c
                    break
                for u in sorted(uses.get(c, {})):
                    if u in inside and u not in previous:
                        previous[u] = c
                        following.append(u)
            queue = following
        chain = [last]
        while previous[chain[-1]] is not None:
            chain.append(previous[chain[-1]])
        chain.reverse()
        steps = []
        for a, b in zip(chain, chain[1:] + [first]):
            path, target, line = uses[a][b]
            steps.append("  %s:%d includes %s" % (path, line, target))
        cycles.append("%s\n%s\n  (all of %s are in one cycle)" % (" -> ".join(chain + [first]), "\n".join(steps),
                                                                  ", ".join(members)))
    return cycles


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cycles = find_cycles(root)
    for cycle in cycles:
        print("include cycle: " + cycle)
    if not cycles:
        print("include_cycles: no cycle among %d files" % len(project_files(root)))
    return 1 if cycles else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
