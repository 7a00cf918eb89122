#!/usr/bin/env python3
"""The serial protocol's tables in docs/serial-protocol.md from the lists
(firmware/link/sxlink_commands.h, sxlink_payloads.h), printed by the protocol-doc program:
the command table and one field table per payload, each between its markers.

  tools/protocol_doc.py --write --exe build/host/tests/protocol-doc   rewrite the tables
  tools/protocol_doc.py --check --exe build/host/tests/protocol-doc   compare (exit 1 if stale)
"""
import argparse
import os
import subprocess
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "serial-protocol.md")
BLOCKS = ("commands", "ST", "PF", "FR", "TL", "OP", "CA", "CS", "CT", "CR2")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    ap.add_argument("--exe", required=True, help="the protocol-doc program")
    a = ap.parse_args()
    if not os.access(a.exe, os.X_OK):
        print("protocol_doc: no program at %s (build the protocol-doc target)" % a.exe,
              file=sys.stderr)
        return 1
    status = 0
    for name in BLOCKS:
        out = subprocess.run([a.exe, name], capture_output=True, text=True, check=False)
        if out.returncode != 0:
            print("protocol_doc: %s %s failed: %s" % (a.exe, name, out.stderr.strip()),
                  file=sys.stderr)
            return 1
        begin = "<!-- protocol-doc %s: tools/protocol_doc.py --write -->" % name
        end = "<!-- /protocol-doc %s -->" % name
        status |= sim_doc_table.update_block("protocol_doc", DOC, begin, end, out.stdout, a)
    return status


if __name__ == "__main__":
    sys.exit(main())
