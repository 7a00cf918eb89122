#!/usr/bin/env python3
"""The F28335 image as TI's linker would build it, checked without TI's tools.

usage: image_check.py --linker FILE.cmd [--define NAME=VALUE]... --objects DIR
                      --callgraph DIR --asm FILE.asm... [--stack-words N]
                      [--isr fw_adc_isr] [--entry main] [--copy fw_ramfuncs_copy]
                      [--from-flash-file FILE] [--from-flash FN,...] [--summary FILE.json]

A model of the TI linker's rules (SPRU513, "Linker Description") for exactly the constructs
the firmware's linker command files use, applied to the section list of a 32-bit Arm proxy
build of the same sources (tools/check_target_memory.sh builds it):

  MEMORY      `NAME : origin = X, length = Y` under `PAGE 0 :` / `PAGE 1 :`
  SECTIONS    `name : > RANGE`, `name : >> A | B` (split in order), `LOAD = A, RUN = B`,
              `PAGE = n`, `TYPE = DSECT` (not loaded), `LOAD_START(sym)` and the like;
              `#if` / `#ifdef` / `#ifndef` / `#else` / `#endif` on the build's --define macros
  input specs `*(sect)`, `*file.*obj(sect)` (file names as CMake's `file.c.obj` and CCS's
              `file.obj`), `-l lib<member member>(sect)` and `-l lib(sect)`; `sect` matches
              that section and its subsections (`.text` matches `.text:_f`)
Allocation: an input section goes to the output section whose explicit specification names
it; input sections no specification names go to the output section of their own (base) name
("additional input sections with the same name as an output section are linked at its end",
SPRU513). A section two specifications name is an error here (the model does not lean on
precedence rules), as is one no rule takes (TI would place it by default heuristics) and a
specification that takes nothing (a misspelt function, member or file).

Input sections of the model, as cl2000 (COFF ABI, --gen_func_subsections=on) names them:
  - each proxy function section `.text.f` -> `.text:_f`; SIXPHASE_RAMFUNC functions
    (sixphase_placement.h) -> `.TI.ramfunc`; `.rodata*` -> `.econst`; SIXPHASE_RAMCONST
    tables -> `ramconsts`; `.bss*`, `.data*` -> `.ebss` (initialised data adds `.cinit`);
  - `.switch` for every object whose source has a `switch` statement (cl2000 may build a
    jump table for it; the proxy cannot tell, so the model assumes it does);
  - the assembly sources' sections (`.sect "name"`, `.text`);
  - the run-time library members the image pulls in (RTS_MEMBERS below: the boot chain, and
    the routines standing for the proxy's helper calls), each a `.text`;
  - `.stack` of --stack-words.

Checks (each failure is reported, all of them, then the exit status is 1):
  1. boot: everything executed from the reset vector until the RAM copy is done
     (codestart, the run-time library's boot chain, and main up to --copy in source order)
     runs where it is loaded;
  2. period code: every function the control interrupt (--isr) reaches, except what only the
     --from-flash functions reach, runs from RAM where it exists out of line; every function
     that runs from RAM is such a function (or one that must by necessity: RAM_BY_NECESSITY);
  3. run-time library: the members the period calls run from RAM, and no other member does;
  4. constants: every table the period's code reads runs from RAM, and every table copied to
     RAM is read by it; the jump tables (`.switch`) of an object run from RAM exactly when a
     function of the period in it has a `switch`;
  5. memory: no range overflows; a RAM range that takes code, tables or `.ebss` keeps
     RAM_LIMIT free. Sizes: code C28x words = CODE_FACTOR x proxy bytes / 2 (see there),
     tables bytes / 2, static data DATA_FACTOR x bytes / 2, run-time library members by
     allowance.
"""
import argparse
import fnmatch
import json
import math
import os
import re
import subprocess
import sys

import stack_depth

# C28x words per proxy (Thumb-2) halfword of code. Both instruction sets mix 16- and 32-bit
# instructions; the C28x moves 32-bit data through the accumulator (MOVL pairs), needs FPU
# pipeline delay slots and has fewer addressing forms, so its code is taken as 1.0 to 1.5
# times the proxy's halfwords. The check takes the pessimistic end.
CODE_FACTOR = (1.0, 1.5)
DATA_FACTOR = 1.5   # 16-bit char and bool on the C28x make small structs larger
RAM_LIMIT = 0.90    # the most of a RAM range the estimate may fill
SWITCH_WORDS = 16   # allowance for one object's jump tables
STACK_SECTION = ".stack"

# The members of TI's rts2800_fpu32.lib this image can pull in: the symbols they define and a
# size allowance in words (the library is not available here; the real sizes are in the map
# file). Names as C2000 code generation tools 18.x and later build them (`*.asm.obj`,
# `*.c.obj`; older releases: `l_div.obj` and so on).
RTS_LIB = "rts2800_fpu32.lib"
RTS_MEMBERS = {
    "boot28.asm.obj": (("_c_int00",), 96),
    "pre_init.c.obj": (("__system_pre_init",), 8),
    "startup.c.obj": (("__system_post_cinit",), 8),
    "args_main.c.obj": (("_args_main",), 32),
    "exit.c.obj": (("_exit", "_abort"), 64),
    "_lock.c.obj": (("__nop", "__register_lock", "__register_unlock"), 32),
    "fs_div28.asm.obj": (("FS$$DIV",), 64),
    "i_div28.asm.obj": (("I$$DIV", "I$$MOD", "U$$DIV", "U$$MOD"), 64),
    "l_div28.asm.obj": (("L$$DIV", "L$$MOD", "UL$$DIV", "UL$$MOD"), 96),
    "ll_div28.asm.obj": (("LL$$DIV", "LL$$MOD", "ULL$$DIV", "ULL$$MOD"), 256),
    "ll_mpy28.asm.obj": (("LL$$MPY",), 64),
}
# TI's boot28.asm: the reset entry _c_int00 runs the pre-init hook, initialises the C
# environment (.cinit), calls the post-cinit hook and main through _args_main, then exit.
BOOT_CHAIN = (("_c_int00", "__system_pre_init"), ("_c_int00", "__system_post_cinit"),
              ("_c_int00", "_args_main"), ("_c_int00", "_exit"), ("_args_main", "main"),
              ("_exit", "_abort"), ("_exit", "__nop"))
BOOT_BEFORE_MAIN = ("_c_int00", "__system_pre_init", "__system_post_cinit", "_args_main")
# A proxy helper call (gcc, Cortex-M0: no divide instruction, no FPU) and the run-time library
# members it may stand for on the C28x, where int is 16 bits: an integer division of the proxy
# may be a 16-bit (I$$, U$$) or a 32-bit (L$$, UL$$) one there. COFF double is 32 bits.
DIVISION = ("i_div28.asm.obj", "l_div28.asm.obj")
HELPER_MEMBERS = {
    "__aeabi_fdiv": ("fs_div28.asm.obj",), "__aeabi_ddiv": ("fs_div28.asm.obj",),
    "__aeabi_idiv": DIVISION, "__aeabi_idivmod": DIVISION,
    "__aeabi_uidiv": DIVISION, "__aeabi_uidivmod": DIVISION,
    "__aeabi_ldivmod": ("ll_div28.asm.obj",), "__aeabi_uldivmod": ("ll_div28.asm.obj",),
    "__aeabi_lmul": ("ll_mpy28.asm.obj",),
}
# Helpers that are instructions on the C28x with the FPU32 (no library call): float
# arithmetic, compares and conversions, 64-bit shifts, a bit scan gcc recognised in a C loop
# (cl2000 compiles the loop), and the block copies and clears gcc makes of struct assignments
# and zeroing loops (memcpy, memset: the sources call neither; cl2000 copies inline, RPT).
INSTRUCTION_HELPERS = re.compile(
    r"^__aeabi_(fadd|fsub|frsub|fmul|fcmp\w+|cfcmp\w+|f2iz|f2uiz|i2f|ui2f|dadd|dsub|dmul|"
    r"dcmp\w+|d2iz|d2uiz|i2d|ui2d|f2d|d2f|llsl|llsr|lasr)$|^__(clz|ctz)[sd]i2$|"
    r"^mem(cpy|set)$")
# String literals of the proxy: only the intrinsic stand-ins' names (f28335_compiler.h,
# f28335_proxy_intrinsic("EALLOW")); cl2000 emits the instruction instead.
PROXY_STRINGS = re.compile(r"^\.rodata(\.[\w.]*)?\.str[\d.]*$")
# Functions that run from RAM although the period does not call them.
RAM_BY_NECESSITY = {
    "f28335_flash_init": "sets the flash wait states: TI forbids running that from flash",
}
PROXY_OBJECT = re.compile(r"^(.*)\.o$")
# The F28335's SARAM (M0, M1, L0..L7), word addresses: what runs there was copied or is data.
RAM_WINDOWS = ((0x000000, 0x000800), (0x008000, 0x010000))


class Fail(Exception):
    pass


def preprocess(text, defines):
    """The linker file after TI's preprocessing of #if/#ifdef/#ifndef/#else/#endif."""
    out, stack = [], []
    for line in text.splitlines():
        d = re.match(r"\s*#\s*(ifdef|ifndef|if|else|endif)\b\s*(\w*)", line)
        if not d:
            out.append(line if all(stack) else "")
            continue
        kind, name = d.groups()
        if kind in ("ifdef", "ifndef", "if"):
            value = defines.get(name)
            stack.append({"ifdef": value is not None, "ifndef": value is None,
                          "if": value not in (None, "0")}[kind])
        elif not stack:
            raise Fail("#%s without #if in the linker file" % kind)
        elif kind == "else":
            stack[-1] = not stack[-1]
        else:
            stack.pop()
        out.append("")
    if stack:
        raise Fail("unterminated #if in the linker file")
    return "\n".join(out)


def strip_comments(text):
    return re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)


def block_body(text, keyword):
    m = re.search(r"\b%s\s*\{" % keyword, text)
    if not m:
        raise Fail("no %s { } in the linker file" % keyword)
    depth, i = 1, m.end()
    while depth and i < len(text):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    if depth:
        raise Fail("unbalanced braces in %s" % keyword)
    return text[m.end():i - 1]


def parse_memory(text):
    ranges, page = {}, None
    for line in block_body(text, "MEMORY").splitlines():
        p = re.match(r"\s*PAGE\s+(\d+)\s*:", line)
        if p:
            page = int(p.group(1))
            line = line[p.end():]
        m = re.match(r"\s*(\w+)\s*:\s*origin\s*=\s*(0x[0-9A-Fa-f]+|\d+)\s*,\s*"
                     r"length\s*=\s*(0x[0-9A-Fa-f]+|\d+)", line)
        if m:
            if page is None:
                raise Fail("memory range %s outside a PAGE" % m.group(1))
            origin, length = int(m.group(2), 0), int(m.group(3), 0)
            ranges[m.group(1)] = {"page": page, "origin": origin, "length": length,
                                  "ram": any(lo <= origin and origin + length <= hi
                                             for lo, hi in RAM_WINDOWS)}
    if not ranges:
        raise Fail("no memory ranges in MEMORY")
    return ranges


SPEC = re.compile(r"(-l\s*)?([^\s(<]+)(?:<([^>]*)>)?\s*\(([^)]*)\)")


def parse_specs(body, where):
    """Input specifications of an output section's { } list."""
    specs, rest = [], body
    for m in SPEC.finditer(body):
        lib, name, members, sections = m.groups()
        specs.append({"text": " ".join(m.group(0).split()), "library": bool(lib) or bool(members),
                      "file": name, "members": members.replace(",", " ").split()
                      if members is not None else None,
                      "sections": sections.replace(",", " ").split(), "taken": 0})
        rest = rest.replace(m.group(0), " ", 1)
    if rest.strip():
        raise Fail("%s: cannot read '%s' in the input list" % (where, rest.strip()[:60]))
    return specs


def parse_placement(name, attrs, ranges, problems):
    flat = " ".join(attrs.split())
    out = {"name": name, "dsect": bool(re.search(r"TYPE\s*=\s*DSECT", flat))}
    page = re.search(r"PAGE\s*=\s*(\d+)", flat)
    out["page"] = int(page.group(1)) if page else 0
    load = re.search(r"LOAD\s*=\s*([\w|\s]+?)(?:,|$|\s+RUN|\s+PAGE)", flat)
    run = re.search(r"RUN\s*=\s*([\w|\s]+?)(?:,|$|\s+LOAD|\s+PAGE)", flat)
    to = re.search(r"(>>|>)\s*([\w|\s]+?)(?:,|$|\s+PAGE)", flat)
    if load or run:
        if not (load and run):
            raise Fail("%s: LOAD without RUN or RUN without LOAD" % name)
        out["load"] = [r.strip() for r in load.group(1).split("|")]
        out["run"] = [r.strip() for r in run.group(1).split("|")]
    elif to:
        out["load"] = out["run"] = [r.strip() for r in to.group(2).split("|")]
        if to.group(1) == ">" and len(out["load"]) > 1:
            raise Fail("%s: '>' with several ranges needs '>>'" % name)
    else:
        raise Fail("%s: no memory range" % name)
    for r in out["load"] + out["run"]:
        if r not in ranges:
            raise Fail("%s: unknown memory range %s" % (name, r))
        if ranges[r]["page"] != out["page"]:
            problems.append("%s: memory range %s is not on PAGE %d (TI's linker finds no range "
                            "of that name there)" % (name, r, out["page"]))
    return out


def parse_sections(text, ranges, problems):
    body = block_body(text, "SECTIONS")
    starts = [m for m in re.finditer(r"(?m)^\s*([.\w$]+)\s*:", body)]
    outputs = []
    for i, m in enumerate(starts):
        end = starts[i + 1].start() if i + 1 < len(starts) else len(body)
        chunk = body[m.end():end]
        specs = None
        brace = re.match(r"\s*\{", chunk)
        if brace:
            close = chunk.index("}")
            specs = parse_specs(chunk[brace.end():close], m.group(1))
            chunk = chunk[close + 1:]
        out = parse_placement(m.group(1), chunk, ranges, problems)
        out["specs"] = specs
        outputs.append(out)
    return outputs


def parse_linker(path, defines, problems):
    """Memory ranges and output sections; what TI's linker would refuse goes to problems."""
    text = strip_comments(preprocess(open(path).read(), defines))
    ranges = parse_memory(text)
    return ranges, parse_sections(text, ranges, problems)


# ---- input sections of the model ------------------------------------------------------------

def readelf(tool, flag, path):
    return subprocess.run([tool, flag, "-W", path], stdout=subprocess.PIPE, check=True,
                          text=True).stdout


def elf_sections(tool, path):
    """{index: (name, size)} of an object's allocated sections."""
    out = {}
    for m in re.finditer(r"^\s*\[\s*(\d+)\]\s+(\S+)\s+\S+\s+[0-9a-f]+\s+[0-9a-f]+\s+"
                         r"([0-9a-f]+)\s+\S+\s+(\S*)", readelf(tool, "-S", path), re.M):
        if "A" in m.group(4):
            out[int(m.group(1))] = (m.group(2), int(m.group(3), 16))
    return out


def elf_symbols(tool, path):
    """[(name, type, section index, size)] of an object's defined symbols."""
    syms = []
    for m in re.finditer(r"^\s*\d+:\s+[0-9a-f]+\s+(\d+)\s+(\w+)\s+\w+\s+\w+\s+(\w+)\s+(\S+)$",
                         readelf(tool, "-s", path), re.M):
        size, kind, ndx, name = m.groups()
        if ndx.isdigit():
            syms.append((name, kind, int(ndx), int(size)))
        elif ndx == "COM":
            syms.append((name, "COMMON", -1, int(size)))
    return syms


def elf_relocations(tool, path):
    """{section name: set of symbol names} its relocations refer to."""
    refs, current = {}, None
    for line in readelf(tool, "-r", path).splitlines():
        head = re.match(r"Relocation section '\.rela?(\S+)'", line)
        if head:
            current = refs.setdefault(head.group(1), set())
            continue
        entry = re.match(r"^[0-9a-f]+\s+[0-9a-f]+\s+\S+\s+[0-9a-f]+\s+(\S+)", line)
        if entry and current is not None:
            current.add(entry.group(1))
    return refs


def ti_section(name):
    """The cl2000 (COFF) input section that a proxy section stands for."""
    if name.startswith(".text."):
        return ".text:_" + stack_depth.c_name(name[len(".text."):])
    if name in (".TI.ramfunc", "ramconsts"):
        return name
    if name.startswith(".rodata"):
        return ".econst"
    if name.startswith((".bss", ".data", ".sbss", ".sdata")):
        return ".ebss"
    if name == ".text":
        return ".text"
    return None


def code_words(nbytes):
    return int(math.ceil(CODE_FACTOR[1] * nbytes / 2.0))


def data_words(section, nbytes):
    factor = DATA_FACTOR if section in (".ebss", ".cinit") else 1.0
    return int(math.ceil(factor * nbytes / 2.0))


class Input(object):
    """One input section of the model: a file (object or library member), a section name,
    its C28x words, the functions and data symbols it holds."""

    def __init__(self, file, section, words, library=None):
        self.file, self.section, self.words, self.library = file, section, words, library
        self.functions, self.data = set(), set()
        self.output = None
        self.taken_by = []

    def label(self):
        where = "%s<%s>" % (self.library, self.file) if self.library else self.file
        return "%s(%s)" % (where, self.section)


def object_inputs(tool, path, source_text):
    """Input sections of one proxy object, and {data symbol: input} for its tables."""
    name = PROXY_OBJECT.match(os.path.basename(path)).group(1) + ".c.obj"
    sections = elf_sections(tool, path)
    merged, symbols = {}, {}
    for index, (sname, size) in sorted(sections.items()):
        ti = ti_section(sname)
        if ti is None or size == 0:
            continue
        code = ti.startswith(".text") or ti == ".TI.ramfunc"
        words = code_words(size) if code else data_words(ti, size)
        key = ti
        if key not in merged:
            merged[key] = Input(name, ti, 0)
        merged[key].words += words
        symbols[index] = merged[key]
        if sname.startswith(".data") and size:
            merged.setdefault(".cinit", Input(name, ".cinit", 0)).words += words + 2
    commons = [s for s in elf_symbols(tool, path) if s[1] == "COMMON"]
    if commons:
        ebss = merged.setdefault(".ebss", Input(name, ".ebss", 0))
        ebss.words += sum(data_words(".ebss", s[3]) for s in commons)
    by_symbol = {}
    for sym, kind, ndx, _ in elf_symbols(tool, path):
        holder = symbols.get(ndx)
        if holder is None:
            continue
        if kind == "FUNC":
            holder.functions.add(stack_depth.c_name(sym))
        elif kind == "OBJECT":
            holder.data.add(sym)
            by_symbol[sym] = holder
        elif kind == "SECTION":
            by_symbol[sections[ndx][0]] = holder
    if switch_functions(source_text):
        merged[".switch"] = Input(name, ".switch", SWITCH_WORDS)
    return name, list(merged.values()), by_symbol


FUNCTION_START = re.compile(r"^(?![ \t#/*{}])[^;=(\n]*?\b(\w+)\s*\(", re.M)


def function_bodies(source_text):
    """{function name: body text} of a C file in the project's format (a definition starts at
    column 0, its body's braces are at column 0)."""
    bodies = {}
    for m in FUNCTION_START.finditer(source_text):
        brace = source_text.find("\n{", m.end())
        semicolon = source_text.find(";", m.end())
        if brace < 0 or 0 <= semicolon < brace:
            continue
        end = source_text.find("\n}", brace)
        if end >= 0:
            bodies[m.group(1)] = source_text[brace:end + 2]
    return bodies


def switch_functions(source_text):
    return set(fn for fn, body in function_bodies(source_text).items()
               if re.search(r"\bswitch\s*\(", body))


def asm_inputs(path):
    """Input sections of an assembly source (their labels as functions) and its branches:
    (object name, [Input], [(label, target)])."""
    name = os.path.basename(path) + ".obj"
    inputs, current, calls, last = {}, None, [], None
    for line in open(path):
        code = line.split(";", 1)[0]
        sect = re.match(r"\s+\.sect\s+\"([^\"]+)\"", code)
        if sect or re.match(r"\s+\.text\b", code):
            current = sect.group(1) if sect else ".text"
            inputs.setdefault(current, Input(name, current, 0))
            continue
        label = re.match(r"^(\w+):", code)
        if label and current:
            inputs[current].functions.add(label.group(1))
            last = label.group(1)
            continue
        instr = code.split()
        if current and instr and not instr[0].startswith("."):
            inputs[current].words += 2   # at most two words an instruction
            if instr[0] in ("LB", "LCR") and len(instr) > 1:
                calls.append((last, instr[1].lstrip("#")))
    return name, list(inputs.values()), calls


def rts_inputs(helpers):
    """The library members the image pulls in: the boot chain and those standing for the
    helper calls of the whole image."""
    wanted = set(m for m, (syms, _) in RTS_MEMBERS.items()
                 if set(syms) & set(a for pair in BOOT_CHAIN for a in pair))
    for helper in helpers:
        wanted.update(members_for(helper))
    inputs = []
    for member in sorted(wanted):
        symbols, words = RTS_MEMBERS[member]
        item = Input(member, ".text", words, library=RTS_LIB)
        item.functions.update(symbols)
        inputs.append(item)
    return inputs


def members_for(helper):
    if helper in HELPER_MEMBERS:
        return HELPER_MEMBERS[helper]
    if INSTRUCTION_HELPERS.match(helper):
        return ()
    raise Fail("no C28x run-time library routine is known for the proxy's %s: add it to "
               "HELPER_MEMBERS or INSTRUCTION_HELPERS in tools/image_check.py" % helper)


# ---- allocation -----------------------------------------------------------------------------

def base_name(section):
    return section.split(":", 1)[0]


def section_matches(pattern, section):
    return fnmatch.fnmatchcase(section, pattern) or fnmatch.fnmatchcase(base_name(section),
                                                                         pattern)


def spec_takes(spec, item):
    if not any(section_matches(p, item.section) for p in spec["sections"]):
        return False
    if spec["library"]:
        if item.library is None or os.path.basename(spec["file"]) != item.library:
            return False
        return spec["members"] is None or item.file in spec["members"]
    if item.library is not None:
        return spec["file"] == "*"
    stem = item.file[:-len(".c.obj")] if item.file.endswith(".c.obj") else item.file
    return fnmatch.fnmatchcase(item.file, spec["file"]) or \
        fnmatch.fnmatchcase(stem + ".obj", spec["file"])


def allocate(outputs, inputs, errors):
    """Puts every input section into its output section (the rules in the module doc)."""
    for out in outputs:
        for spec in out["specs"] or ():
            for item in inputs:
                if spec_takes(spec, item):
                    spec["taken"] += 1
                    item.taken_by.append((out, spec))
    for item in inputs:
        if len(item.taken_by) > 1:
            errors.append("%s is named by two rules: %s" % (item.label(), "; ".join(
                "%s in %s" % (spec["text"], out["name"]) for out, spec in item.taken_by)))
        if item.taken_by:
            item.output = item.taken_by[0][0]
            continue
        by_name = [o for o in outputs if o["name"] == base_name(item.section)]
        if by_name:
            item.output = by_name[0]
        elif item.words:
            errors.append("%s matches no rule of the linker file" % item.label())
    for out in outputs:
        for spec in out["specs"] or ():
            if not spec["taken"]:
                errors.append("%s: `%s` takes nothing (no such function, member, file or "
                              "section in the image)" % (out["name"], spec["text"]))


def copied(item):
    out = item.output
    return out is not None and out["run"] != out["load"]


def in_ram(item, ranges):
    out = item.output
    return out is not None and not out["dsect"] and \
        all(r in ranges and ranges[r]["ram"] for r in out["run"])


def fill(outputs, inputs, ranges, errors):
    """Words each memory range holds; overflow and RAM-budget failures."""
    use = dict((r, 0) for r in ranges)
    budgeted = set()   # ranges with more than the stack: the stack has its own bound
    size = dict((o["name"], 0) for o in outputs)
    for item in inputs:
        if item.output is not None and not item.output["dsect"]:
            size[item.output["name"]] += item.words
    for out in outputs:
        if out["dsect"] or not size[out["name"]]:
            continue
        places = [out["load"]] if out["load"] == out["run"] else [out["load"], out["run"]]
        for regions in places:
            left = size[out["name"]]
            for r in regions:
                take = min(left, ranges[r]["length"] - use[r]) if len(regions) > 1 else left
                use[r] += take
                left -= take
                if take and out["name"] != STACK_SECTION:
                    budgeted.add(r)
            if left:
                errors.append("%s (%d words) does not fit %s" % (out["name"], size[out["name"]],
                                                                 " | ".join(regions)))
    for r, words in sorted(use.items()):
        length = ranges[r]["length"]
        if words > length:
            errors.append("memory range %s overflows: %d of %d words" % (r, words, length))
        elif ranges[r]["ram"] and r in budgeted and words > RAM_LIMIT * length:
            errors.append("memory range %s holds %d of %d words, more than %.0f %%"
                          % (r, words, length, 100 * RAM_LIMIT))
    return use, size


# ---- what runs when -------------------------------------------------------------------------

def reachable(edges, roots, stop=()):
    seen, todo = set(roots), list(roots)
    while todo:
        for callee in edges.get(todo.pop(), ()):
            if callee not in seen and callee not in stop:
                seen.add(callee)
                todo.append(callee)
    return seen


CALL = re.compile(r"\b([A-Za-z_]\w*)\s*\(")
NOT_CALLS = {"if", "for", "while", "switch", "return", "sizeof"}


def calls_in_order(body):
    return [m.group(1) for m in CALL.finditer(body) if m.group(1) not in NOT_CALLS]


def before_copy(fn, copy, edges, bodies, seen=None):
    """Functions `fn` runs up to and including the end of `copy`, by its source order: every
    call before the one that leads to the copy, whole; that call, followed the same way."""
    seen = set() if seen is None else seen
    if fn in seen:
        raise Fail("recursion through %s on the boot path" % fn)
    seen.add(fn)
    ran = {fn}
    if fn == copy:
        return ran | reachable(edges, [fn])
    if fn not in bodies:
        raise Fail("boot path: no source for %s (needed to order its calls before %s)"
                   % (fn, copy))
    for callee in calls_in_order(bodies[fn]):
        if callee == copy or copy in reachable(edges, [callee]):
            return ran | before_copy(callee, copy, edges, bodies, seen)
        ran |= reachable(edges, [callee])
    raise Fail("boot path: %s never reaches %s" % (fn, copy))


def holders(inputs, fn):
    return [i for i in inputs if fn in i.functions]


def check_boot(boot, inputs, errors):
    for fn in sorted(boot):
        for item in holders(inputs, fn):
            if copied(item):
                errors.append("boot: %s (%s) runs before the RAM copy but is linked to run at "
                              "%s: its run address holds nothing yet"
                              % (fn, item.label(), " | ".join(item.output["run"])))


def check_period_code(period, inputs, ranges, errors):
    code = [i for i in inputs if i.library is None and
            (i.section.startswith(".text") or i.section == ".TI.ramfunc")]
    for fn in sorted(period):
        for item in holders(code, fn):
            if not in_ram(item, ranges):
                errors.append("period: %s runs in the control interrupt from flash (%s): mark "
                              "it SIXPHASE_RAMFUNC (sixphase_placement.h)" % (fn, item.label()))
    for fn, why in sorted(RAM_BY_NECESSITY.items()):
        for item in holders(code, fn):
            if not in_ram(item, ranges):
                errors.append("%s must run from RAM (%s) but is in %s" % (fn, why, item.label()))
    for item in code:
        if in_ram(item, ranges):
            for fn in sorted(item.functions - period - set(RAM_BY_NECESSITY)):
                errors.append("period: %s runs from RAM (%s) but the control period never calls "
                              "it" % (fn, item.label()))


def check_library(period_helpers, inputs, ranges, errors):
    needed = {}
    for helper in sorted(period_helpers):
        for member in members_for(helper):
            needed.setdefault(member, helper)
    for item in inputs:
        if item.library is None:
            continue
        ram = in_ram(item, ranges)
        if item.file in needed and not ram:
            errors.append("run-time library: the period calls %s (%s stands for it) but it runs "
                          "from flash: add the member to ramfuncs"
                          % (item.label(), needed[item.file]))
        elif ram and item.file not in needed:
            errors.append("run-time library: %s runs from RAM but the period never calls it"
                          % item.label())
    return sorted(needed)


def check_tables(objects, period, ranges, errors):
    """Constant tables and jump tables of the period's code."""
    tables = {}
    for obj in objects:
        for sym, item in obj["by_symbol"].items():
            if item.section in (".econst", "ramconsts"):
                tables.setdefault(sym, []).append((obj["name"], item))
    read = set()
    for obj in objects:
        for item in obj["inputs"]:
            if item.section != ".TI.ramfunc" or not in_ram(item, ranges):
                continue
            for sym in sorted(obj["relocs"].get(item.section, ())):
                if PROXY_STRINGS.match(sym):
                    continue
                local = obj["by_symbol"].get(sym)
                found = [(obj["name"], local)] if local is not None else tables.get(sym, [])
                for owner, table in found:
                    if table.section not in (".econst", "ramconsts"):
                        continue
                    read.add(id(table))
                    if not in_ram(table, ranges):
                        errors.append("tables: the period's code in %s reads %s (%s), which "
                                      "stays in flash: mark it SIXPHASE_RAMCONST"
                                      % (obj["name"], sym, table.label()))
    for obj in objects:
        for item in obj["inputs"]:
            if item.section == "ramconsts" and id(item) not in read:
                errors.append("tables: %s is copied to RAM but the period's code never reads it"
                              % item.label())
        switch = obj["inputs_by_section"].get(".switch")
        wanted = bool(obj["switch_functions"] & period)
        if switch is not None and wanted != in_ram(switch, ranges):
            errors.append("jump tables: %s %s" % (
                switch.label(), "run from flash but %s (period) has a switch" %
                ", ".join(sorted(obj["switch_functions"] & period)) if wanted else
                "run from RAM but no function of the period in it has a switch"))


# ---- the build ------------------------------------------------------------------------------

def load_objects(a, sources):
    objects = []
    for path in sorted(os.listdir(a.objects)):
        if not path.endswith(".o") or path.startswith("ti_link_stubs"):
            continue
        stem = path[:-2]
        source = sources.get(stem)
        if source is None:
            raise Fail("%s: no source of that name in the call graph" % path)
        text = open(source).read()
        full = os.path.join(a.objects, path)
        name, inputs, by_symbol = object_inputs(a.readelf, full, text)
        objects.append({"name": name, "inputs": inputs, "by_symbol": by_symbol,
                        "inputs_by_section": dict((i.section, i) for i in inputs),
                        "relocs": elf_relocations(a.readelf, full),
                        "switch_functions": switch_functions(text),
                        "bodies": function_bodies(text)})
    if not objects:
        raise Fail("no objects in %s" % a.objects)
    return objects


def load_graph(a):
    files = sorted(os.path.join(a.callgraph, f) for f in os.listdir(a.callgraph)
                   if f.endswith(".ci") and not f.startswith("ti_link_stubs"))
    if not files:
        raise Fail("no .ci files in %s" % a.callgraph)
    _, edges, sites, sources, defined = stack_depth.load_raw(files)
    stack_depth.resolve(defined, edges, sites, sources)
    merged = {}
    for caller, callees in edges.items():
        merged.setdefault(stack_depth.c_name(caller), set()).update(
            stack_depth.c_name(c) for c in callees)
    edges = merged
    by_stem = dict((os.path.splitext(os.path.basename(s))[0], s) for s in sources)
    return edges, set(stack_depth.c_name(d) for d in defined), by_stem


RTS_SYMBOLS = set(sym for syms, _ in RTS_MEMBERS.values() for sym in syms)


def is_helper(fn, defined):
    """A compiler helper the proxy calls (not a function of the sources or of the boot chain)."""
    return fn not in defined and fn not in RTS_SYMBOLS and \
        (fn.startswith("__") or fn in HELPER_MEMBERS or fn in ("memcpy", "memset"))


def from_flash(a, defines):
    """The functions this build runs from flash on purpose: --from-flash-file's (a "fixed:"
    name only in the Q24 link, SIXPHASE_FW_Q24) and --from-flash's."""
    names = set(f for f in a.from_flash.split(",") if f)
    if a.from_flash_file:
        for line in open(a.from_flash_file):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if line.startswith("fixed:"):
                if defines.get("SIXPHASE_FW_Q24") in (None, "0"):
                    continue
                line = line[len("fixed:"):].strip()
            names.add(line)
    return names


def model(a, errors):
    """Builds the model: (ranges, outputs, inputs, objects, period, period helpers, boot,
    the functions in flash on purpose)."""
    defines = dict(d.split("=", 1) if "=" in d else (d, "1") for d in a.define)
    ranges, outputs = parse_linker(a.linker, defines, errors)
    edges, defined, sources = load_graph(a)
    objects = load_objects(a, sources)
    inputs = [i for obj in objects for i in obj["inputs"]]
    boot = set(BOOT_BEFORE_MAIN)
    for path in a.asm:
        _, asm, calls = asm_inputs(path)
        inputs += asm
        boot.update(fn for item in asm for fn in item.functions)
        for caller, callee in calls:
            edges.setdefault(caller, set()).add(callee)
    for caller, callee in BOOT_CHAIN:
        edges.setdefault(caller, set()).add(callee)
    helpers = set(c for callees in edges.values() for c in callees if is_helper(c, defined))
    inputs += rts_inputs(helpers)
    stack = Input("(linker)", STACK_SECTION, a.stack_words)
    inputs.append(stack)
    flash = from_flash(a, defines)
    for fn in sorted(flash | {a.isr, a.entry, a.copy}):
        if fn not in defined:
            raise Fail("%s is not a function of the call graph" % fn)
    reach = reachable(edges, [a.isr], flash)
    period = set(f for f in reach if f in defined)
    period_helpers = set(f for f in reach if is_helper(f, defined))
    bodies = {}
    for obj in objects:
        bodies.update(obj["bodies"])
    boot |= before_copy(a.entry, a.copy, edges, bodies)
    return ranges, outputs, inputs, objects, period, period_helpers, boot, flash


def report(outputs, use, size, ranges):
    print("| output section | load | run | C28x words |")
    print("|---|---|---|---|")
    for out in outputs:
        if size[out["name"]]:
            print("| %s | %s | %s | %d%s |" % (
                out["name"], " or ".join(out["load"]),
                "(same)" if out["run"] == out["load"] else " or ".join(out["run"]),
                size[out["name"]], " (not loaded)" if out["dsect"] else ""))
    for r, words in sorted(use.items()):
        if words:
            print("%s: %d of %d words (%.0f %%)" % (r, words, ranges[r]["length"],
                                                    100.0 * words / ranges[r]["length"]))


def summary(flash, ranges, outputs, use, size, period, members, boot):
    return {"ranges": dict((r, {"length": v["length"], "use": use[r], "ram": v["ram"]})
                           for r, v in ranges.items()),
            "outputs": dict((o["name"], {"words": size[o["name"]], "load": o["load"],
                                         "run": o["run"]})
                            for o in outputs if size[o["name"]] and not o["dsect"]),
            "period_functions": len(period), "rts_in_ram": members,
            "boot_path": sorted(boot),
            "from_flash": sorted(flash),
            "code_factor": list(CODE_FACTOR), "data_factor": DATA_FACTOR,
            "ram_limit": RAM_LIMIT}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--linker", required=True)
    ap.add_argument("--define", action="append", default=[],
                    help="NAME=VALUE: a macro of the build's link (TI: --define)")
    ap.add_argument("--objects", required=True, help="directory of the -O2 proxy objects")
    ap.add_argument("--callgraph", required=True,
                    help="directory of the no-inline Cortex-M0 .ci files (helper calls shown)")
    ap.add_argument("--asm", action="append", default=[], help="assembly source of the image")
    ap.add_argument("--stack-words", type=int, default=0)
    ap.add_argument("--isr", default="fw_adc_isr")
    ap.add_argument("--entry", default="main")
    ap.add_argument("--copy", default="fw_ramfuncs_copy")
    ap.add_argument("--from-flash-file",
                    help="the functions run from flash on purpose, one a line ('#' comments; "
                         "'fixed: NAME' only when the link defines SIXPHASE_FW_Q24)")
    ap.add_argument("--from-flash", default="",
                    help="functions the build leaves in flash on purpose (comma-separated)")
    ap.add_argument("--readelf", default="arm-none-eabi-readelf")
    ap.add_argument("--summary", help="write the figures as JSON")
    a = ap.parse_args()
    try:
        errors = []
        ranges, outputs, inputs, objects, period, helpers, boot, flash = model(a, errors)
        allocate(outputs, inputs, errors)
        check_boot(boot, inputs, errors)
        check_period_code(period, inputs, ranges, errors)
        members = check_library(helpers, inputs, ranges, errors)
        check_tables(objects, period, ranges, errors)
        use, size = fill(outputs, inputs, ranges, errors)
    except (Fail, OSError, subprocess.CalledProcessError) as e:
        sys.stderr.write("image_check: %s\n" % e)
        sys.exit(2)
    report(outputs, use, size, ranges)
    print("boot path before the copy: %s" % ", ".join(sorted(boot)))
    print("period: %d functions; run-time library members it calls: %s"
          % (len(period), ", ".join(members) or "none"))
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump(summary(flash, ranges, outputs, use, size, period, members, boot), f,
                      indent=1, sort_keys=True)
    for e in errors:
        sys.stderr.write("image_check: %s: %s\n" % (os.path.basename(a.linker), e))
    if errors:
        sys.exit(1)
    print("image_check: %s: the image boots, its period runs from RAM, it fits"
          % os.path.basename(a.linker))


if __name__ == "__main__":
    main()
