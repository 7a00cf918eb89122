#!/usr/bin/env python3
"""The host tools' usage in the docs, as the tools print it (issue 26: the docs kept their own
copies, which missed options): `sixphase-sim help` in docs/simulator.md, `sixphase-link --help`
in docs/serial-protocol.md, each between its markers.

  tools/usage_doc.py --write --sim PATH --link PATH   rewrite the blocks
  tools/usage_doc.py --check --sim PATH --link PATH   compare (exit 1 when one differs)
"""
import argparse
import os
import subprocess
import sys

import sim_doc_table

ROOT = sim_doc_table.ROOT
BUILD = os.path.join(ROOT, "build", "host")
# (option naming the program, its default, the argument that prints the usage, the doc, marker)
BLOCKS = (
    ("sim", os.path.join(BUILD, "host_sim", "sixphase-sim"), "help", "docs/simulator.md",
     "sim-usage"),
    ("link", os.path.join(BUILD, "firmware", "sixphase-link"), "--help",
     "docs/serial-protocol.md", "link-usage"),
)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    for opt, default, _, _, _ in BLOCKS:
        ap.add_argument("--" + opt, default=default)
    a = ap.parse_args()
    status = 0
    for opt, _, arg, doc, marker in BLOCKS:
        exe = getattr(a, opt)
        if not os.access(exe, os.X_OK):
            print("usage_doc: no program at %s (build it, or --%s)" % (exe, opt), file=sys.stderr)
            return 1
        out = subprocess.run([exe, arg], capture_output=True, text=True, check=False)
        if out.returncode != 0 or not out.stdout.startswith("usage:"):
            print("usage_doc: %s %s failed: %s" % (exe, arg, out.stderr.strip()), file=sys.stderr)
            return 1
        begin = "<!-- %s: tools/usage_doc.py --write -->" % marker
        end = "<!-- /%s -->" % marker
        status |= sim_doc_table.update_block("usage_doc", os.path.join(ROOT, doc), begin, end,
                                             "```\n" + out.stdout + "```\n", a)
    return status


if __name__ == "__main__":
    sys.exit(main())
