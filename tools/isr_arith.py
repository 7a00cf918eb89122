#!/usr/bin/env python3
"""Run-time-library calls on the per-period path, from gcc's -fcallgraph-info output.

usage: isr_arith.py --root fw_adc_isr --forbid REGEX FILE.ci...

Lists every library helper (names starting with "__") reachable from ROOT and fails when one
matches REGEX, printing the call chain that reaches it. Built for a Cortex-M0 proxy of the
target (tools/check_isr_arith.sh), which has no 64-bit multiply or divide instruction, so every
64-bit integer or double operation on the path shows up as a helper call, as it would on the
C28x (whose 64-bit operations and divisions are run-time-library calls too). Indirect calls
follow the `indirect-call:` notes of the sources (tools/stack_depth.py); an unresolved one fails.
"""
import argparse
import re
import sys

import stack_depth


def reachable(edges, root):
    parent = {root: None}
    todo = [root]
    while todo:
        fn = todo.pop()
        for callee in sorted(edges.get(fn, ())):
            if callee not in parent:
                parent[callee] = fn
                todo.append(callee)
    return parent


def chain(parent, fn):
    out = []
    while fn is not None:
        out.append(fn)
        fn = parent[fn]
    return " <- ".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--forbid", required=True)
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    _, edges = stack_depth.load(args.files)
    if args.root not in edges:
        sys.exit(f"isr_arith: {args.root} not found in the call graph")
    parent = reachable(edges, args.root)
    helpers = sorted(fn for fn in parent if fn.startswith("__"))
    bad = [fn for fn in helpers if re.search(args.forbid, fn)]
    print(f"helpers reachable from {args.root}: {', '.join(helpers) or 'none'}")
    for fn in bad:
        print(f"isr_arith: forbidden on the per-period path: {chain(parent, fn)}", file=sys.stderr)
    if bad:
        sys.exit(1)


if __name__ == "__main__":
    main()
