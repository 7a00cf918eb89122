#!/usr/bin/env python3
"""Worst-case stack depth of call trees from gcc's -fcallgraph-info=su output.

usage: stack_depth.py ROOT FILE.ci...
       stack_depth.py --background ROOT --isr ROOT [--stack-words N]
                      [--margin X] [--context-words N] FILE.ci...

The first form prints the deepest path from ROOT with each frame's size and the total. The
second sums the deepest path of the background (ROOT main) and of an interrupt that can nest
on top of it at any point, and with --stack-words checks the target's stack: the frames are
measured on a 32-bit proxy build in bytes; the C28x counts 16-bit words, so the requirement in
words is taken as margin * bytes / 2 plus the interrupt's saved context (C28x: 14 words saved
by the hardware, the __interrupt prologue's registers, FPU ones included). Exits non-zero if it
does not fit.

Indirect calls (function pointers) are resolved from notes in the sources of the call graph,
kept next to the table or the hook they call through:
    /* indirect-call: CALLER[, CALLER...] -> TARGET[, TARGET...] */
where a TARGET is a function, `table NAME` (every function named in the initializer of the
array NAME in the same file), `prefix P` (every function of the call graph whose name starts
with P and that the same file defines: a table built from a list, whose rows name their
handlers by token pasting) or `external NAME` (a routine outside the compiled sources, not
measured); `nothing` alone says the image never sets the pointer (a hook only a host build
uses). CALLER is the function that makes the call as gcc reports it (list the function
that holds the call and the one it may be inlined into). The tool fails on an indirect call
no note resolves, on a note no indirect call needs, on recursion (the depth would be
unbounded) and on dynamic (VLA / alloca) frames.
"""
import argparse
import json
import math
import re
import sys

INDIRECT = "__indirect_call"
CLONE = re.compile(r"(\.(isra|constprop|part|cold|lto_priv)\.\d+)+$")
NOTE = re.compile(r"indirect-call:[ \t]*([\w \t,]+?)[ \t]*->[ \t]*([\w \t,]+)")


def fail(msg):
    sys.stderr.write("stack_depth: %s\n" % msg)
    sys.exit(1)


def name_of(title):
    """The function's name, without the file of a static one."""
    return title.split(":")[-1]


def c_name(name):
    """The C function a gcc clone comes from (ctl_flux_d.isra.0 is ctl_flux_d specialised)."""
    return CLONE.sub("", name)


def load_raw(paths):
    """Frames, direct edges, indirect call sites (caller, location), the compiled sources and
    the functions they define (frames need -fcallgraph-info=su; the rest does not)."""
    frames, edges, sites, sources, defined = {}, {}, [], [], set()
    for path in paths:
        text = open(path).read()
        graph = re.search(r'graph: \{ title: "([^"]+)"', text)
        if graph:
            sources.append(graph.group(1))
        for m in re.finditer(r'node: \{ title: "([^"]+)" label: "([^"]*)"( shape)?', text):
            name = name_of(m.group(1))
            if not m.group(3):  # declared-only functions are drawn as ellipses
                defined.add(name)
            size = re.search(r"(\d+) bytes \((\w+)", m.group(2))
            if size:
                if size.group(2) != "static":
                    fail("%s has a %s frame" % (name, size.group(2)))
                frames[name] = max(frames.get(name, 0), int(size.group(1)))
        for m in re.finditer(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"'
                             r'(?: label: "([^"]*)")?', text):
            caller, callee = name_of(m.group(1)), name_of(m.group(2))
            if callee == INDIRECT:
                sites.append((caller, m.group(3) or path))
            else:
                edges.setdefault(caller, set()).add(callee)
    return frames, edges, sites, sources, defined


def table_functions(text, table, functions, where):
    """Functions named in the initializer of the array `table`."""
    m = re.search(r"\b%s\s*\[[^\]]*\]\s*=\s*\{" % re.escape(table), text)
    if not m:
        fail("%s: no table %s in that file" % (where, table))
    depth, i = 1, m.end()
    while depth and i < len(text):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    body = re.sub(r"/\*.*?\*/", " ", text[m.end():i], flags=re.S)
    found = sorted(set(w for w in re.findall(r"\b[A-Za-z_]\w*\b", body) if w in functions))
    if not found:
        fail("%s: table %s names no function of the call graph" % (where, table))
    return found


def prefix_functions(text, prefix, functions, where):
    """Functions of the call graph named prefix... that this file defines."""
    found = sorted(f for f in functions if f.startswith(prefix) and
                   re.search(r"^\w[\w \t\*]*\b%s\s*\(" % re.escape(f), text, flags=re.M))
    if not found:
        fail("%s: no function of the call graph starts with %s in that file" % (where, prefix))
    return found


def read_notes(sources, functions):
    """[(where, callers, targets, externals)] from the `indirect-call:` notes."""
    notes = []
    for src in sources:
        try:
            text = open(src).read()
        except OSError:
            fail("cannot read %s (named by the call graph)" % src)
        for m in NOTE.finditer(text):
            where = "%s:%d" % (src, text.count("\n", 0, m.start()) + 1)
            callers = [c for c in re.split(r"[\s,]+", m.group(1)) if c]
            targets, externals = set(), set()
            items = [t.strip() for t in m.group(2).split(",")]
            if items == ["nothing"]:
                items = []
            for item in items:
                words = item.split()
                if len(words) == 2 and words[0] == "table":
                    targets.update(table_functions(text, words[1], functions, where))
                elif len(words) == 2 and words[0] == "prefix":
                    targets.update(prefix_functions(text, words[1], functions, where))
                elif len(words) == 2 and words[0] == "external":
                    externals.add(words[1])
                elif len(words) == 1 and words[0] in functions:
                    targets.add(words[0])
                else:
                    fail("%s: '%s' is not a function of the call graph, a `table NAME`, a "
                         "`prefix P` or an `external NAME`" % (where, item))
            notes.append((where, callers, targets, externals))
    return notes


def resolve(functions, edges, sites, sources):
    """Replaces every indirect call by the functions its note names; returns the resolutions."""
    notes = read_notes(sources, functions)
    by_caller = {}
    for where, callers, targets, externals in notes:
        for c in callers:
            entry = by_caller.setdefault(c, [set(), set(), []])
            entry[0].update(targets)
            entry[1].update(externals)
            entry[2].append(where)
    for caller, location in sites:
        if caller not in by_caller:
            fail("unresolved indirect call in %s (%s): add an `indirect-call: %s -> ...` note "
                 "next to the table or hook it calls through" % (caller, location, caller))
        targets, externals, _ = by_caller[caller]
        edges.setdefault(caller, set()).update(targets | externals)
    callers_with_sites = set(c for c, _ in sites)
    for where, callers, _, _ in notes:
        if not callers_with_sites.intersection(callers):
            fail("%s: no indirect call in %s (stale note)" % (where, ", ".join(callers)))
    return {c: sorted(by_caller[c][0] | by_caller[c][1]) for c in sorted(callers_with_sites)}


def load(paths):
    """Frames and edges with every indirect call resolved (fails on an unresolved one)."""
    frames, edges, sites, sources, defined = load_raw(paths)
    resolve(defined, edges, sites, sources)
    return frames, edges


class CallGraph:
    def __init__(self, frames, edges):
        self.frames = frames
        self.edges = edges
        self.external = set()
        self.memo = {}

    def deepest(self, fn, stack=()):
        if fn in stack:
            fail("recursion through %s" % " -> ".join(stack + (fn,)))
        if fn in self.memo:
            return self.memo[fn]
        if fn not in self.frames:
            self.external.add(fn)
            return (0, [fn + " (not measured)"])
        best = (0, [])
        for callee in sorted(self.edges.get(fn, ())):
            d = self.deepest(callee, stack + (fn,))
            if d[0] > best[0]:
                best = d
        self.memo[fn] = (self.frames[fn] + best[0], ["%s (%d)" % (fn, self.frames[fn])] + best[1])
        return self.memo[fn]

    def report(self, root):
        if root not in self.frames:
            fail("root %s not found" % root)
        total, path = self.deepest(root)
        print("worst-case stack from %s: %d bytes" % (root, total))
        print("path: " + " -> ".join(path))
        return total, path

    def print_external(self):
        print("not measured: " + ", ".join(sorted(e for e in self.external
                                                  if not e.startswith("__aeabi"))))
        print("compiler runtime helpers (leaf routines, small frames): " +
              ", ".join(sorted(e for e in self.external if e.startswith("__aeabi"))))


def load_graph(files):
    frames, edges, sites, sources, defined = load_raw(files)
    for caller, targets in resolve(defined, edges, sites, sources).items():
        print("indirect calls of %s: %s" % (caller, ", ".join(targets)))
    return CallGraph(frames, edges)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--background")
    ap.add_argument("--isr")
    ap.add_argument("--stack-words", type=int)
    ap.add_argument("--margin", type=float, default=1.5)
    ap.add_argument("--context-words", type=int, default=64)
    ap.add_argument("--summary", help="write the figures as JSON")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    if a.background is None and a.isr is None:
        root, files = a.files[0], a.files[1:]
        if not files:
            fail("usage: stack_depth.py ROOT FILE.ci...")
        graph = load_graph(files)
        graph.report(root)
        graph.print_external()
        return
    if a.background is None or a.isr is None:
        fail("--background and --isr go together")
    graph = load_graph(a.files)
    background, background_path = graph.report(a.background)
    isr, isr_path = graph.report(a.isr)
    graph.print_external()
    need = int(math.ceil(a.margin * (background + isr) / 2.0)) + a.context_words
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump({"background_bytes": background, "isr_bytes": isr, "need_words": need,
                       "background_path": background_path, "isr_path": isr_path,
                       "margin": a.margin, "context_words": a.context_words}, f)
    print("background + nested ISR: %d bytes on the proxy; C28x requirement %d words "
          "(%.1f x bytes / 2 + %d words of interrupt context)"
          % (background + isr, need, a.margin, a.context_words))
    if a.stack_words is not None:
        print("linked stack: %d words (0x%X): %s" % (
            a.stack_words, a.stack_words, "fits" if need <= a.stack_words else "TOO SMALL"))
        if need > a.stack_words:
            fail("the stack needs %d words, the link reserves %d" % (need, a.stack_words))


if __name__ == "__main__":
    main()
