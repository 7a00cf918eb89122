#!/usr/bin/env python3
"""RAM placement and budget of the F28335 image from a 32-bit proxy build
(tools/check_target_memory.sh).

usage: ram_budget.py --linker F28335_flash.cmd [--define NAME=VALUE]... --objects DIR
                     --callgraph DIR [--isr fw_adc_isr] [--from-flash FN,...]
                     [--size arm-none-eabi-size] [--summary FILE.json]

The linker command file is read as TI's linker reads it, preprocessed with the build's
--define macros (#if / #ifdef / #ifndef / #else / #endif). What it copies to RAM:
  - ramfuncs: the code of the per-period path, one `*(.text:_NAME)` line per function (cl2000
    --gen_func_subsections puts each function in a subsection of that name), or
    `*OBJECT.*obj(.text:_NAME)` for a static inline function of a shared private header that
    only one object's copy must run from RAM (the others' may stay in flash; the placement check
    goes by name, the sizes by object), plus every function
    marked F28335_RAMFUNC (`*(ramfuncs)`) and the run-time library (`-l...lib(.text)`);
  - ramconsts: constant tables, one `*NAME.*obj(.econst)` line per object;
and the blocks they and `.ebss` run in.

Placement check: every function the control interrupt (--isr) can reach, in the call graph of
a build without inlining (--callgraph: gcc -fno-inline -fcallgraph-info, indirect calls
resolved as tools/stack_depth.py does), must run from RAM, except what only the --from-flash
functions reach (a build that leaves a controller in flash on purpose). A missing function
fails the check with the line to add.

Budget: sizes measured in the proxy objects (--objects: gcc -O2 -ffunction-sections, so each
function is a `.text.NAME` section; a function inlined there costs nothing of its own). Proxy
bytes to C28x words:
  - tables and static data: words = bytes / 2, exact for arrays of 16- and 32-bit values
    (the C28x's 16-bit char and bool make small structs larger: the data gets the margin);
  - code: words = margin * bytes / 2, for the unknown density of C28x code against Thumb-2.
The run-time library routines (division, 64-bit helpers) cannot be measured here; a fixed
reserve stands for them. Fails if a block holds more than LIMIT of its size.
"""
import argparse
import glob
import json
import math
import os
import re
import subprocess
import sys

import stack_depth

MARGIN = 1.5
RTS_RESERVE_WORDS = 1024  # FPU32 run-time routines called from the period (division, 64-bit)
LIMIT = 0.90              # the most of a block the estimate may fill
PROXY_SECTIONS = {".econst": (".rodata",), ".ebss": (".bss", ".data")}
LIBRARY = re.compile(r"^(__|mem(cpy|set|move)$)")  # compiler helpers: the run-time library


def fail(msg):
    sys.stderr.write("ram_budget: %s\n" % msg)
    sys.exit(1)


def preprocess(text, defines):
    """The linker file after TI's preprocessing of #if/#ifdef/#ifndef/#else/#endif."""
    out, stack = [], []
    for line in text.splitlines():
        d = re.match(r"\s*#\s*(ifdef|ifndef|if|else|endif)\b\s*(\w*)", line)
        if not d:
            if all(stack):
                out.append(line)
            continue
        kind, name = d.groups()
        if kind in ("ifdef", "ifndef", "if"):
            value = defines.get(name)
            on = {"ifdef": value is not None, "ifndef": value is None,
                  "if": value not in (None, "0")}[kind]
            stack.append(on)
        elif not stack:
            fail("#%s without #if in the linker file" % kind)
        elif kind == "else":
            stack[-1] = not stack[-1]
        else:
            stack.pop()
    if stack:
        fail("unterminated #if in the linker file")
    return "\n".join(out)


def copied_section(text, name):
    """Body of a copied output section and the block it runs in."""
    block = re.search(r"\b%s\s*:\s*\{(.*?)\}\s*LOAD\s*=\s*\w+,\s*RUN\s*=\s*(\w+)" % name, text,
                      re.S)
    if not block:
        fail("no %s section with LOAD and RUN in the linker file" % name)
    return re.sub(r"/\*.*?\*/", " ", block.group(1), flags=re.S), block.group(2)


def parse_linker(path, defines):
    text = preprocess(open(path).read(), defines)
    regions = {m.group(1): int(m.group(2), 16) for m in re.finditer(
        r"^\s*(\w+)\s*:\s*origin\s*=\s*0x[0-9A-Fa-f]+,\s*length\s*=\s*(0x[0-9A-Fa-f]+)",
        text, re.M)}
    ebss = re.search(r"^\s*\.ebss\s*:\s*>\s*(\w+)", text, re.M)
    if not ebss:
        fail("%s: no .ebss placement" % path)
    code, code_region = copied_section(text, "ramfuncs")
    functions = re.findall(r"\*\(\.text:_(\w+)\)", code)
    only_in = {fn: obj for obj, fn in re.findall(r"\*(\w+)\.\*obj\(\.text:_(\w+)\)", code)}
    if not functions or "*(ramfuncs)" not in code.replace(" ", ""):
        fail("ramfuncs lists no `*(.text:_NAME)` function or lacks `*(ramfuncs)`")
    tables, tables_region = copied_section(text, "ramconsts")
    placed = re.findall(r"\*(\w+)\.\*obj\((\.\w+)\)", tables)
    if not placed:
        fail("no object list in ramconsts")
    code_listing = (set(functions) | set(only_in), only_in, code_region)
    return regions, code_listing, (placed, tables_region), ebss.group(1)


def section_sizes(size_tool, obj):
    out = subprocess.run([size_tool, "-A", obj], stdout=subprocess.PIPE, check=True,
                         text=True).stdout
    sizes = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) >= 2 and f[0].startswith(".") and f[1].isdigit():
            sizes[f[0]] = sizes.get(f[0], 0) + int(f[1])
    return sizes


def proxy_bytes(sizes, target_section):
    return sum(n for name, n in sizes.items()
               if any(name == p or name.startswith(p + ".") for p in PROXY_SECTIONS[target_section]))


def ramfunc_pragmas(sources):
    """Functions the sources place in ramfuncs themselves (F28335_RAMFUNC)."""
    names = set()
    for src in sources:
        names.update(re.findall(r"\bF28335_RAMFUNC\((\w+)\)", open(src).read()))
    return names


def reachable(edges, root, stop):
    seen, todo = {root}, [root]
    while todo:
        for callee in edges.get(todo.pop(), ()):
            if callee not in seen and callee not in stop:
                seen.add(callee)
                todo.append(callee)
    return seen


def check_placement(a, listed):
    """Functions of the period's path that the linker file leaves in flash (must be none)."""
    files = sorted(glob.glob(os.path.join(a.callgraph, "*.ci")))
    if not files:
        fail("no .ci files in %s" % a.callgraph)
    _, edges, sites, sources, defined = stack_depth.load_raw(files)
    stack_depth.resolve(defined, edges, sites, sources)
    flash = set(f for f in a.from_flash.split(",") if f)
    if a.isr not in defined:
        fail("%s is not in the call graph" % a.isr)
    for fn in sorted(flash):
        if fn not in defined:
            fail("--from-flash %s is not a function of the call graph" % fn)
        if fn in listed:
            fail("%s is listed in ramfuncs and named --from-flash" % fn)
    in_ram = listed | ramfunc_pragmas(sources)
    path = set(stack_depth.c_name(fn) for fn in reachable(edges, a.isr, flash) if fn in defined)
    missing = sorted(fn for fn in path - in_ram if not LIBRARY.match(fn))
    for fn in missing:
        sys.stderr.write("ram_budget: %s runs in the control interrupt but from flash: add "
                         "`*(.text:_%s)` to ramfuncs in the linker file\n" % (fn, fn))
    print("per-period path: %d functions, %s%s" % (
        len(path), "%d of them missing from ramfuncs" % len(missing) if missing else
        "all in ramfuncs", "; in flash on purpose: " + ", ".join(sorted(flash)) if flash else ""))
    return missing


def measure(a, listed, only_in, placed):
    """Proxy bytes of the listed code (a function listed for one object: that object's copy
    only), of the copied tables and of all static data."""
    objs = {os.path.basename(o)[:-2]: section_sizes(a.size, o)
            for o in sorted(glob.glob(os.path.join(a.objects, "*.o")))
            if not os.path.basename(o).startswith("ti_link_stubs")}
    if not objs:
        fail("no objects in %s" % a.objects)
    code = sum(n for obj, sizes in objs.items() for name, n in sizes.items()
               if name.startswith(".text.") and stack_depth.c_name(name[6:]) in listed
               and only_in.get(stack_depth.c_name(name[6:]), obj) == obj)
    tables = 0
    for name, section in placed:
        if name not in objs:
            fail("the linker file copies %s, which is not a source of the image" % name)
        tables += proxy_bytes(objs[name], section)
    ebss = sum(proxy_bytes(s, ".ebss") for s in objs.values())
    return code, tables, ebss


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--linker", required=True)
    ap.add_argument("--define", action="append", default=[],
                    help="NAME=VALUE: a macro of the build's link (TI: --define)")
    ap.add_argument("--objects", required=True, help="directory of the -O2 proxy objects")
    ap.add_argument("--callgraph", required=True, help="directory of the no-inline .ci files")
    ap.add_argument("--isr", default="fw_adc_isr")
    ap.add_argument("--from-flash", default="",
                    help="functions this build leaves in flash on purpose (comma-separated)")
    ap.add_argument("--size", default="arm-none-eabi-size")
    ap.add_argument("--summary", help="write the figures as JSON")
    a = ap.parse_args()
    defines = dict(d.split("=", 1) if "=" in d else (d, "1") for d in a.define)
    regions, (listed, only_in, code_region), (placed, tables_region), ebss_region = \
        parse_linker(a.linker, defines)
    missing = check_placement(a, listed)
    code_bytes, table_bytes, ebss_bytes = measure(a, listed, only_in, placed)
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
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump({"code_words": code_words, "table_words": table_words,
                       "ebss_words": ebss_words, "code_region": code_region,
                       "data_region": ebss_region, "regions": regions, "use": use,
                       "from_flash": sorted(f for f in a.from_flash.split(",") if f)}, f)
    over = [r for r, need in sorted(use.items()) if need > LIMIT * regions[r]]
    for region in over:
        sys.stderr.write("ram_budget: %s needs %d words, more than %.0f %% of its %d\n"
                         % (region, use[region], 100 * LIMIT, regions[region]))
    if missing or over:
        sys.exit(1)


if __name__ == "__main__":
    main()
