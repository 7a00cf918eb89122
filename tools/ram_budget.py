#!/usr/bin/env python3
"""RAM budget of the F28335 image from a 32-bit proxy build (tools/check_target_memory.sh).

usage: ram_budget.py --linker F28335_flash.cmd [--size arm-none-eabi-size] OBJ.o...

Reads from the linker command file what it copies to RAM - the output sections `ramfuncs`
(code) and `ramconsts` (constant tables), one `*NAME.*obj(SECTION)` line per object and
section - and the blocks they and `.ebss` run in; measures those sections in the proxy
objects; checks that each block holds what goes into it. Proxy bytes to C28x words:
  - tables and static data: words = bytes / 2, exact for arrays of 16- and 32-bit values
    (the C28x's 16-bit char and bool make small structs larger: the data gets the margin);
  - code: words = margin * bytes / 2, for the unknown density of C28x code against Thumb-2.
The run-time library routines the linker file also copies (-l rts2800_fpu32.lib) cannot be
measured here; a fixed reserve stands for them. Exits non-zero if a block overflows.
"""
import argparse
import math
import os
import re
import subprocess
import sys

MARGIN = 1.5
RTS_RESERVE_WORDS = 1024  # FPU32 run-time routines called from the period (division, 64-bit)
PROXY_SECTIONS = {".text": (".text",), ".econst": (".rodata",), ".ebss": (".bss", ".data")}


def fail(msg):
    sys.stderr.write("ram_budget: %s\n" % msg)
    sys.exit(1)


def copied_section(text, name):
    """Objects and sections of a copied output section, and the block it runs in."""
    block = re.search(r"\b%s\s*:\s*\{(.*?)\}\s*LOAD\s*=\s*\w+,\s*RUN\s*=\s*(\w+)" % name, text,
                      re.S)
    if not block:
        fail("no %s section with LOAD and RUN in the linker file" % name)
    placed = re.findall(r"\*(\w+)\.\*obj\((\.\w+)\)", block.group(1))
    if not placed:
        fail("no object list in %s" % name)
    return placed, block.group(2)


def parse_linker(path):
    text = open(path).read()
    regions = {m.group(1): int(m.group(2), 16) for m in re.finditer(
        r"^\s*(\w+)\s*:\s*origin\s*=\s*0x[0-9A-Fa-f]+,\s*length\s*=\s*(0x[0-9A-Fa-f]+)",
        text, re.M)}
    ebss = re.search(r"^\s*\.ebss\s*:\s*>\s*(\w+)", text, re.M)
    if not ebss:
        fail("%s: no .ebss placement" % path)
    return regions, copied_section(text, "ramfuncs"), copied_section(text, "ramconsts"), \
        ebss.group(1)


def section_sizes(size_tool, obj):
    out = subprocess.run([size_tool, "-A", obj], stdout=subprocess.PIPE, check=True,
                         text=True).stdout
    sizes = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) >= 2 and f[0].startswith(".") and f[1].isdigit():
            sizes[f[0]] = int(f[1])
    return sizes


def proxy_bytes(sizes, target_section):
    return sum(n for name, n in sizes.items()
               if any(name == p or name.startswith(p + ".") for p in PROXY_SECTIONS[target_section]))


def placed_bytes(objs, placed):
    total = 0
    for name, section in placed:
        if name not in objs:
            fail("the linker file copies %s, which is not a source of the image" % name)
        total += proxy_bytes(objs[name], section)
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--linker", required=True)
    ap.add_argument("--size", default="arm-none-eabi-size")
    ap.add_argument("--report-only", action="store_true",
                    help="print the budget, do not fail on an overflow")
    ap.add_argument("objects", nargs="+")
    a = ap.parse_args()
    regions, (code, code_region), (tables, tables_region), ebss_region = parse_linker(a.linker)
    objs = {os.path.basename(o)[:-2]: section_sizes(a.size, o) for o in a.objects
            if not os.path.basename(o).startswith("ti_link_stubs")}
    code_bytes = placed_bytes(objs, code)
    table_bytes = placed_bytes(objs, tables)
    ebss_bytes = sum(proxy_bytes(s, ".ebss") for s in objs.values())
    code_words = int(math.ceil(MARGIN * code_bytes / 2.0)) + RTS_RESERVE_WORDS
    table_words = (table_bytes + 1) // 2
    ebss_words = int(math.ceil(MARGIN * ebss_bytes / 2.0))
    use = {code_region: code_words}
    use[tables_region] = use.get(tables_region, 0) + table_words
    use[ebss_region] = use.get(ebss_region, 0) + ebss_words
    print("| what | proxy bytes | C28x words | block |")
    print("|---|---|---|---|")
    print("| ramfuncs: per-period code | %d | %d (%.1f x bytes / 2 + %d RTS reserve) | %s |"
          % (code_bytes, code_words, MARGIN, RTS_RESERVE_WORDS, code_region))
    print("| ramconsts: its constant tables | %d | %d | %s |" % (table_bytes, table_words,
                                                                tables_region))
    print("| .ebss: all static data | %d | %d (%.1f x bytes / 2) | %s |"
          % (ebss_bytes, ebss_words, MARGIN, ebss_region))
    for region, need in sorted(use.items()):
        print("%s: %d of %d words (%.0f %%)" % (region, need, regions[region],
                                                100.0 * need / regions[region]))
    for region, need in use.items():
        if need > regions[region] and not a.report_only:
            fail("%s needs %d words, the block holds %d" % (region, need, regions[region]))


if __name__ == "__main__":
    main()
