#!/usr/bin/env python3
"""The simulator's usage in docs/simulator.md, as `sixphase-sim help` prints it (issue 26: the
doc kept its own copy, which missed options).

  tools/sim_usage_doc.py --write [--sim PATH]   rewrite the block
  tools/sim_usage_doc.py --check [--sim PATH]   compare (exit 1 when it differs)
"""
import os
import subprocess
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "simulator.md")
BEGIN = "<!-- sim-usage: tools/sim_usage_doc.py --write -->"
END = "<!-- /sim-usage -->"


def main():
    a = sim_doc_table.parser(__doc__.splitlines()[0], "docs/simulator.md").parse_args()
    if not sim_doc_table.usable("sim_usage_doc", a):
        return 1
    out = subprocess.run([a.sim, "help"], capture_output=True, text=True, check=False)
    if out.returncode != 0 or not out.stdout.startswith("usage:"):
        print("sim_usage_doc: %s help failed: %s" % (a.sim, out.stderr.strip()), file=sys.stderr)
        return 1
    return sim_doc_table.update_block("sim_usage_doc", DOC, BEGIN, END,
                                      "```\n" + out.stdout + "```\n", a)


if __name__ == "__main__":
    sys.exit(main())
