#!/usr/bin/env python3
"""Worst-case stack depth of call trees from gcc's -fcallgraph-info=su output.

usage: stack_depth.py ROOT FILE.ci...
       stack_depth.py --background ROOT --isr ROOT [--indirect FN,...] [--stack-words N]
                      [--margin X] [--context-words N] FILE.ci...

The first form prints the deepest path from ROOT with each frame's size and the total. The
second sums the deepest path of the background (ROOT main) and of an interrupt that can nest
on top of it at any point, and with --stack-words checks the target's stack: the frames are
measured on a 32-bit proxy build in bytes; the C28x counts 16-bit words, so the requirement in
words is taken as margin * bytes / 2 plus the interrupt's saved context (C28x: 14 words saved
by the hardware, the __interrupt prologue's registers, FPU ones included). Exits non-zero if it
does not fit.

--indirect lists the functions an indirect call can reach (function pointers the call graph
cannot follow); the deepest of them is charged to every indirect call. Fails on recursion (the
depth would be unbounded) and on dynamic (VLA / alloca) frames.
"""
import argparse
import re
import math
import sys


def fail(msg):
    sys.stderr.write("stack_depth: %s\n" % msg)
    sys.exit(1)


def load(paths):
    frames, edges = {}, {}
    for path in paths:
        text = open(path).read()
        for m in re.finditer(r'node: \{ title: "([^"]+)" label: "([^"]*)"', text):
            name = m.group(1).split(":")[-1]
            size = re.search(r"(\d+) bytes \((\w+)", m.group(2))
            if size:
                if size.group(2) != "static":
                    fail("%s has a %s frame" % (name, size.group(2)))
                frames[name] = max(frames.get(name, 0), int(size.group(1)))
        for m in re.finditer(
                r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', text):
            edges.setdefault(m.group(1).split(":")[-1], set()).add(m.group(2).split(":")[-1])
    return frames, edges


class CallGraph:
    def __init__(self, frames, edges, indirect):
        self.frames = frames
        self.edges = edges
        if indirect:
            self.edges["__indirect_call"] = set(indirect)
            self.frames.setdefault("__indirect_call", 0)
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
        return total

    def print_external(self):
        print("not measured: " + ", ".join(sorted(e for e in self.external
                                                  if not e.startswith("__aeabi"))))
        print("compiler runtime helpers (leaf routines, small frames): " +
              ", ".join(sorted(e for e in self.external if e.startswith("__aeabi"))))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--background")
    ap.add_argument("--isr")
    ap.add_argument("--indirect", default="")
    ap.add_argument("--stack-words", type=int)
    ap.add_argument("--margin", type=float, default=1.5)
    ap.add_argument("--context-words", type=int, default=64)
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    if a.background is None and a.isr is None:
        root, files = a.files[0], a.files[1:]
        if not files:
            fail("usage: stack_depth.py ROOT FILE.ci...")
        graph = CallGraph(*load(files), indirect=[f for f in a.indirect.split(",") if f])
        graph.report(root)
        graph.print_external()
        return
    if a.background is None or a.isr is None:
        fail("--background and --isr go together")
    graph = CallGraph(*load(a.files), indirect=[f for f in a.indirect.split(",") if f])
    background = graph.report(a.background)
    isr = graph.report(a.isr)
    graph.print_external()
    need = int(math.ceil(a.margin * (background + isr) / 2.0)) + a.context_words
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
