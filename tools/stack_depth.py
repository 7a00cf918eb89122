#!/usr/bin/env python3
"""Worst-case stack depth of a call tree from gcc's -fcallgraph-info=su output.

usage: stack_depth.py ROOT FILE.ci...
Prints the deepest path from ROOT with each frame's size, the total, and the functions the
call graph reaches whose frames are not in the given files (their size is not counted).
Fails on recursion (the depth would be unbounded) and on dynamic (VLA / alloca) frames.
"""
import re
import sys


def main():
    if len(sys.argv) < 3:
        sys.stderr.write("stack_depth: usage: stack_depth.py ROOT FILE.ci...\n")
        sys.exit(2)
    root = sys.argv[1]
    frames, edges = {}, {}
    for path in sys.argv[2:]:
        text = open(path).read()
        for m in re.finditer(r'node: \{ title: "([^"]+)" label: "([^"]*)"', text):
            name = m.group(1).split(":")[-1]
            size = re.search(r"(\d+) bytes \((\w+)", m.group(2))
            if size:
                if size.group(2) != "static":
                    sys.stderr.write("stack_depth: %s has a %s frame\n" % (name, size.group(2)))
                    sys.exit(1)
                frames[name] = max(frames.get(name, 0), int(size.group(1)))
        for m in re.finditer(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', text):
            edges.setdefault(m.group(1).split(":")[-1], set()).add(m.group(2).split(":")[-1])
    if root not in frames:
        sys.stderr.write("stack_depth: root %s not found\n" % root)
        sys.exit(1)
    external = set()
    memo = {}

    def deepest(fn, stack):
        if fn in stack:
            sys.stderr.write("stack_depth: recursion through %s\n" % " -> ".join(stack + [fn]))
            sys.exit(1)
        if fn in memo:
            return memo[fn]
        if fn not in frames:
            external.add(fn)
            return (0, [fn + " (not measured)"])
        best = (0, [])
        for callee in sorted(edges.get(fn, ())):
            d = deepest(callee, stack + [fn])
            if d[0] > best[0]:
                best = d
        memo[fn] = (frames[fn] + best[0], ["%s (%d bytes)" % (fn, frames[fn])] + best[1])
        return memo[fn]

    total, path = deepest(root, [])
    print("worst-case stack from %s: %d bytes" % (root, total))
    print("path: " + " -> ".join(path))
    print("not measured: " + ", ".join(sorted(e for e in external if not e.startswith("__aeabi"))))
    print("compiler runtime helpers (leaf routines, small frames): " +
          ", ".join(sorted(e for e in external if e.startswith("__aeabi"))))


if __name__ == "__main__":
    main()
