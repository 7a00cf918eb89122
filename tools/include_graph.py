#!/usr/bin/env python3
"""The project's include graph (issue 26): fails on an include cycle between modules and on an
include from a folder to a folder its rule does not allow.

A module is a .c file and the .h of the same name in the same folder (x.c includes y.h while
y.c includes x.h is a cycle, as is a header including a header that includes it). An
`#include "name"` resolves against the including file's folder, then the include folders
(--include, in order; the project's by default); a name found in none of them (a system or
test-framework header) is not part of the graph.

Folder rules: a folder's README.md may hold one line `May include: a, b/c, ...` (folders
relative to the root, a folder also allowing everything under it; `nothing`: none). Then every include from a
file of that folder must resolve in the folder itself or in one of those. --require-rules DIR:
every folder under DIR that holds a .c or .h must have such a line.

--known FILE: cycles not yet broken, one a line as this tool prints them ("a <-> b"); each is
reported but passes, and a listed cycle that is no longer there fails (the list only shrinks).

usage: include_graph.py [--root DIR] [--include DIR]... [--require-rules DIR]... [--known FILE]
                        [--layers] [SOURCE_DIR...]
exit 0: no cycle, no rule broken; 1: cycles or broken rules (listed on stderr)."""
import argparse
import pathlib
import re
import sys

# The include folders of the build (CMakeLists.txt files), in the order a compiler sees them;
# host_sim's and firmware/app's folders are reached from host_sim and firmware/app themselves
# ("plant/plant.h", "drive/drive.h").
DEFAULT_INCLUDES = ["control/include", "control/platform", "control/src", "hal/include",
                    "hal/sim", "hal/f28335/include", "firmware/app", "firmware/link",
                    "firmware/tools", "firmware/f28335", "firmware/pil", "hal/mps2", "host_sim",
                    "tools/bench"]
DEFAULT_SOURCES = ["control", "hal", "firmware", "host_sim", "tools/bench"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
RULE = re.compile(r"^May include:(.*)$", re.M)


def scan(root, sources):
    files = []
    for s in sources:
        d = root / s
        if not d.is_dir():
            sys.exit(f"include_graph: no such folder: {d}")
        files += [p for p in sorted(d.rglob("*")) if p.suffix in (".c", ".h") and p.is_file()]
    return files


def resolve(root, f, name, includes):
    for d in [f.parent] + [root / i for i in includes]:
        p = d / name
        if p.is_file():
            return p.resolve()
    return None


def module(root, p, pairs=None):
    """A .c is its header's module when it includes the header of its own name (x.c and
    include/x.h as well as x.c and x.h)."""
    if pairs is not None and p in pairs:
        p = pairs[p]
    return str(p.relative_to(root).with_suffix(""))


def folder_of(mod):
    return str(pathlib.PurePosixPath(mod).parent)


def edges_of(root, files, includes):
    """{module: {module: [(file, line text, included file)]}}"""
    resolved, pairs = {}, {}
    for f in files:
        f = f.resolve()
        resolved[f] = []
        for match in INCLUDE.finditer(f.read_text(errors="replace")):
            p = resolve(root, f, match.group(1), includes)
            if p is not None and root in p.parents:
                resolved[f].append((p, match.group(0).strip()))
                if f.suffix == ".c" and p.suffix == ".h" and p.stem == f.stem:
                    pairs[f] = p
    graph = {}
    for f, incs in resolved.items():
        m = module(root, f, pairs)
        graph.setdefault(m, {})
        for p, line in incs:
            target = module(root, p, pairs)
            if target != m:
                graph[m].setdefault(target, []).append(
                    (str(f.relative_to(root)), line, str(p.relative_to(root))))
                graph.setdefault(target, {})
    return graph


def cycles(graph):
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return sorted(out)


def rules_of(root, folders):
    rules = {}
    for folder in folders:
        readme = root / folder / "README.md"
        if readme.is_file():
            m = RULE.search(readme.read_text())
            if m:
                listed = [x.strip().strip("/") for x in m.group(1).split(",")]
                rules[folder] = [x for x in listed if x and x != "nothing"]
    return rules


def allowed(target_folder, own, allow):
    if target_folder == own:
        return True
    return any(target_folder == a or target_folder.startswith(a + "/") for a in allow)


def layers(graph):
    """Each module's layer: 0 includes nothing of the graph, else 1 + its highest include's."""
    depth = {}

    def of(m, seen):
        if m in depth:
            return depth[m]
        if m in seen:
            return 0  # a cycle (reported separately)
        seen.add(m)
        depth[m] = 1 + max((of(t, seen) for t in graph[m]), default=-1)
        return depth[m]

    for m in graph:
        of(m, set())
    return depth


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent))
    ap.add_argument("--include", action="append")
    ap.add_argument("--require-rules", action="append", default=[])
    ap.add_argument("--known", help="file of the cycles not yet broken")
    ap.add_argument("--layers", action="store_true", help="print each module's layer")
    ap.add_argument("sources", nargs="*")
    args = ap.parse_args()
    root = pathlib.Path(args.root).resolve()
    includes = args.include if args.include is not None else DEFAULT_INCLUDES
    sources = args.sources or [s for s in DEFAULT_SOURCES if (root / s).is_dir()]
    files = scan(root, sources)
    graph = edges_of(root, files, includes)
    problems = 0

    known = set()
    if args.known:
        for line in pathlib.Path(args.known).read_text().splitlines():
            if line.strip() and not line.lstrip().startswith("#"):
                known.add(" <-> ".join(sorted(m.strip() for m in line.split("<->"))))
    found = cycles(graph)
    for comp in found:
        name = " <-> ".join(comp)
        if name in known:
            print(f"known include cycle (not yet broken): {name}", file=sys.stderr)
            continue
        problems += 1
        print(f"include cycle: {name}", file=sys.stderr)
        for m in comp:
            for t in comp:
                for f, line, _ in graph[m].get(t, []):
                    print(f"  {f}: {line}", file=sys.stderr)

    for name in sorted(known - {" <-> ".join(c) for c in found}):
        problems += 1
        print(f"known cycle no longer there, take it off {args.known}: {name}", file=sys.stderr)

    folders = sorted({folder_of(str(f.relative_to(root))) for f in files})
    rules = rules_of(root, folders)
    for req in args.require_rules:
        req = req.strip("/")
        for folder in folders:
            under = req in ("", ".") or folder == req or folder.startswith(req + "/")
            if under and folder not in rules:
                problems += 1
                print(f"no rule: {folder}/README.md has no 'May include:' line", file=sys.stderr)
    for m in sorted(graph):
        for t in sorted(graph[m]):
            for f, line, target in graph[m][t]:
                own, tf = folder_of(f), folder_of(target)
                if own in rules and not allowed(tf, own, rules[own]):
                    problems += 1
                    print(f"rule broken: {f}: {line} ({own} may not include {tf})",
                          file=sys.stderr)

    if args.layers:
        depth = layers(graph)
        for m in sorted(graph, key=lambda k: (depth[k], k)):
            print(f"{depth[m]:3d} {m}")
    n_edges = sum(len(v) for v in graph.values())
    print(f"include_graph: {len(files)} files, {len(graph)} modules, {n_edges} module includes, "
          f"{len(rules)} folder rules; {problems} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
