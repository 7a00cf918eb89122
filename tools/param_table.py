#!/usr/bin/env python3
"""The parameter ranges' table of docs/design.md from the one list
(control/include/ctl_param_ranges.h), printed by the param-table program.

  tools/param_table.py --write --exe build/host/tests/param-table   rewrite the table
  tools/param_table.py --check --exe build/host/tests/param-table   compare (exit 1 if stale)
"""
import os
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "design.md")
BEGIN = "<!-- param-table: tools/param_table.py --write -->"
END = "<!-- /param-table -->"


def main():
    a = sim_doc_table.program_parser(__doc__.splitlines()[0], "param-table").parse_args()
    table = sim_doc_table.program_output("param_table", a.exe, "param-table")
    if table is None:
        return 1
    return sim_doc_table.update_block("param_table", DOC, BEGIN, END, table, a)

if __name__ == "__main__":
    sys.exit(main())
