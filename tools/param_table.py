#!/usr/bin/env python3
"""The parameter ranges' table of docs/design.md from the one list
(control/include/ctl_param_ranges.h), printed by the param-table program.

  tools/param_table.py --write --exe build/host/tests/param-table   rewrite the table
  tools/param_table.py --check --exe build/host/tests/param-table   compare (exit 1 if stale)
"""
import argparse
import os
import subprocess
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "design.md")
BEGIN = "<!-- param-table: tools/param_table.py --write -->"
END = "<!-- /param-table -->"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    ap.add_argument("--exe", required=True, help="the param-table program")
    a = ap.parse_args()
    if not os.access(a.exe, os.X_OK):
        print("param_table: no program at %s (build the param-table target)" % a.exe,
              file=sys.stderr)
        return 1
    out = subprocess.run([a.exe], capture_output=True, text=True, check=False)
    if out.returncode != 0:
        print("param_table: %s failed: %s" % (a.exe, out.stderr.strip()), file=sys.stderr)
        return 1
    return sim_doc_table.update_block("param_table", DOC, BEGIN, END, out.stdout, a)


if __name__ == "__main__":
    sys.exit(main())
