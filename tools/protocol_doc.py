#!/usr/bin/env python3
"""The serial protocol's tables in docs/serial-protocol.md from the lists
(firmware/link/sxlink_commands.h, sxlink_payloads.h), printed by the protocol-doc program:
the command table and one field table per payload, each between its markers.

  tools/protocol_doc.py --write --exe build/host/tests/protocol-doc   rewrite the tables
  tools/protocol_doc.py --check --exe build/host/tests/protocol-doc   compare (exit 1 if stale)
"""
import os
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "serial-protocol.md")
BLOCKS = ("commands", "ST", "PF", "FR", "TL", "OP", "CA", "CS", "CT", "CR2")


def main():
    a = sim_doc_table.program_parser(__doc__.splitlines()[0], "protocol-doc").parse_args()
    status = 0
    for name in BLOCKS:
        table = sim_doc_table.program_output("protocol_doc", a.exe, "protocol-doc", [name])
        if table is None:
            return 1
        begin = "<!-- protocol-doc %s: tools/protocol_doc.py --write -->" % name
        end = "<!-- /protocol-doc %s -->" % name
        status |= sim_doc_table.update_block("protocol_doc", DOC, begin, end, table, a)
    return status

if __name__ == "__main__":
    sys.exit(main())
