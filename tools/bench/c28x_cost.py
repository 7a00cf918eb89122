#!/usr/bin/env python3
"""F28335 cost model of a control step (issue 28 item 4): every host instruction that the step
executes, counted per address by callgrind (`--dump-instr=yes --collect-jumps=yes`), is
classified from the binary's disassembly (objdump) and priced with an interval of C28x / FPU32
cycles per class. The intervals and their sources are PRICES below; run_benchmark.py writes them
into docs/performance.md with the results. A host instruction is not a C28x instruction: each
interval covers the C28x sequence that cl2000 would plausibly emit for what the host instruction
does (a 64-bit multiply of Q24 values is a 32 x 32 -> 64 multiply sequence, an x86 memory-operand
compare is a load plus a compare, a float compare feeding a branch is CMPF32 + MOVST0, ...).

usage (stand-alone): c28x_cost.py BINARY CALLGRIND_DUMP [--points N]
"""
import argparse
import collections
import re
import subprocess
import sys

# Sources, cited by key in the price table (documents are TI's; sections as in the revisions named).
SOURCES = {
    "SPRU430": "SPRU430F, TMS320C28x CPU and Instruction Set Reference Guide: ch. 4 (pipeline, "
               "read/write protection, ARn conflicts) and ch. 6 (per-instruction cycles)",
    "SPRUEO2": "SPRUEO2, TMS320C28x Floating Point Unit and Instruction Set Reference Guide: "
               "pipeline (2p instructions, delay slots) and per-instruction descriptions",
    "SPRAAN9": "SPRAAN9, C28x FPU primer (compiler use of the FPU; division and square root "
               "as estimate + Newton steps)",
    "SPRACN6": "SPRACN6, Fast Integer Division on C2000: table 4 (cycles of the C operator '/' "
               "on the C28x without the FINTDIV unit)",
    "model": "this model's mapping of the host instruction to a C28x sequence (see note)",
}

# class: (description, low, high, sources, note). Cycles per executed host instruction; for the
# conditional branches per taken or not-taken execution.
PRICES = collections.OrderedDict([
    ("load", ("integer load, 32 bits or narrower", 1, 2, "SPRU430",
              "MOV/MOVL/MOVU ACC,loc: 1 cycle; +1 for a read-after-write or ARn-update conflict")),
    ("store", ("integer store, 32 bits or narrower", 1, 2, "SPRU430",
               "MOV/MOVL loc,ACC: 1 cycle; +1 for a pipeline conflict")),
    ("ldst64", ("64-bit load or store (int64, or a pointer on x86-64)", 1, 3, "SPRU430",
                "a pointer is one MOVL (C28x pointers are 22/32 bits), an int64 two MOVL (ACC, P), "
                "+1 conflict")),
    ("mov", ("register copy, sign or zero extension", 0, 1, "SPRU430",
             "often none after register allocation; MOV/MOVL register to register 1")),
    ("const64", ("64-bit immediate (movabs)", 2, 4, "SPRU430",
                 "two to four 16-bit immediates (MOV AH/AL,#16bit, MOVL P,...)")),
    ("lea", ("address arithmetic (lea)", 0, 2, "SPRU430",
             "folded into *+XARn[k] addressing, or ADDB/ADDL XARn 1; scaled forms 2")),
    ("alu", ("integer add/sub/logic/neg/not, 32 bits or narrower", 1, 2, "SPRU430",
             "ADDL/SUBL/AND/OR/XOR/NEG ACC 1 cycle; a 32-bit logic immediate takes two 16-bit "
             "halves")),
    ("alu64", ("integer add/sub/logic/neg, 64 bits", 1, 3, "SPRU430",
               "pointer arithmetic 1; int64: ADDUL P + ADDCL ACC (or SUBUL/SUBBL, NEG64) 2, +1 "
               "to bring the operand into ACC:P")),
    ("alu_mem", ("ALU operation with a memory operand", 1, 3, "SPRU430",
                 "the C28x is an accumulator machine: ADDL ACC,loc32 / ADDL loc32,ACC 1 cycle; "
                 "64-bit or read-modify-write sequences up to 3")),
    ("shift", ("shift or rotate, 32 bits or narrower", 1, 2, "SPRU430",
               "LSL/LSR/ASR ACC,#n or ACC,T 1 cycle; +1 to load T for a variable count")),
    ("shift64", ("shift, 64 bits", 1, 3, "SPRU430",
                 "LSL64/LSR64/ASR64 ACC:P by 1..16 per instruction: 1, a shift by 17..32 two, "
                 "+1 to move the result out of ACC:P")),
    ("mul32", ("integer multiply, 32 x 32 -> 32", 2, 3, "SPRU430",
               "MOVL XT,loc32 + IMPYL ACC,XT,loc32 (2)")),
    ("mul32x32", ("integer multiply, 64-bit result of two 32-bit operands (Q24 products)", 4, 5,
                  "SPRU430",
                  "MOVL XT + IMPYL P,XT + QMPYL ACC,XT = 4..5 (IMPYXUL/QMPYXUL where an operand "
                  "is unsigned); both operands shown 32-bit in the block (sign- or zero-extended "
                  "or a 32-bit immediate)")),
    ("mul64", ("integer multiply, 64-bit result, an operand not shown 32-bit", 4, 10, "SPRU430",
               "a 32 x 32 product 4..5 as above; a 64 x 32 product (IMPYXUL, QMPYL, partial "
               "sums) up to 10")),
    ("mulwide", ("multiply to 128 bits (mul/imul with one operand)", 8, 30, "SPRU430",
                 "64 x 64 partial products (IMPYXUL/QMPYL/IMPYL with carries) or the run-time "
                 "library's LL$$MPY")),
    ("div32", ("integer divide, 32 bits", 37, 63, "SPRACN6",
               "C '/' through the run-time library: u32/u32 37, i32/i32 59, i32 modulo 63 cycles")),
    ("div64", ("integer divide, 64 bits", 54, 2631, "SPRACN6",
               "i64/u64 division through the run-time library, 54 to 2631 cycles")),
    ("clz", ("count leading zeros (bsr/lzcnt)", 25, 45, "SPRU430",
             "the TI build of ctl_qmath.c's top_bit is a five-step binary search (compare + branch "
             "each, taken 7 / not taken 4, plus the shifts and adds)")),
    ("cmp", ("integer compare/test, 32 bits or narrower (register or memory)", 1, 2, "SPRU430",
             "CMPL ACC,loc32 / CMP / TBIT 1 cycle; +1 to load a register operand")),
    ("cmp64", ("integer compare/test, 64 bits", 2, 4, "SPRU430",
               "operands into ACC:P, then CMP64 or SUBUL/SUBBL and the sign test")),
    ("jcc_taken", ("conditional branch, taken", 4, 7, "SPRU430",
                   "B/SB cond taken 7 cycles, BF taken 4")),
    ("jcc_not", ("conditional branch, not taken", 1, 4, "SPRU430",
                 "B/SB/BF not taken 4; 1 where cl2000 uses a conditional instruction instead "
                 "(MOVB AL,#k,cond, MINL/MAXL, SAT)")),
    ("jp", ("parity branch after a float compare (x86 NaN test)", 0, 1, "model",
            "no counterpart on the C28x, where the compare's flags decide directly")),
    ("jmp", ("unconditional direct jump", 4, 7, "SPRU430",
             "BF/LB unconditional 4, SB/B 7")),
    ("jmp_ind", ("indirect jump (switch table)", 6, 9, "SPRU430",
                 "table load 1 + MOVL XAR7 1 + LB *XAR7 4, +3 for the XAR7 update conflict")),
    ("call", ("function call", 4, 5, "SPRU430",
              "LCR #22bit 4 (+1 frame allocation ADDB SP,#k)")),
    ("call_ind", ("indirect call", 5, 6, "SPRU430", "LCR *XARn 4, +1 frame, +1 conflict")),
    ("ret", ("return", 4, 5, "SPRU430", "LRETR 4 (+1 frame release SUBB SP,#k)")),
    ("push", ("push/pop of a saved register", 1, 2, "SPRU430",
              "MOVL *SP++,XARn / MOVL XARn,*--SP 1; +1 conflict")),
    ("cmov", ("conditional move", 1, 4, "SPRU430",
              "MOVB/MOVL conditional 1, or a branch around a move (not taken 4)")),
    ("setcc", ("set byte on condition", 2, 5, "SPRU430",
               "MOVB AL,#0 + MOVB AL,#1,cond 2, or with a branch 5")),
    ("nop", ("no-operation, padding", 0, 0, "model", "not executed work")),
    ("f_arith", ("float add/sub/mul/min/max/abs, register", 1, 2, "SPRUEO2",
                 "ADDF32/SUBF32/MPYF32 are 2p: 1 cycle plus one delay slot that stalls when the "
                 "next instruction needs the result; MINF32/MAXF32/ABSF32 1")),
    ("f_arith_mem", ("float add/sub/mul with a memory operand", 2, 3, "SPRUEO2",
                     "MOV32 RaH,mem32 1 + the 2p operation")),
    ("f_div", ("float divide", 16, 30, "SPRAAN9",
               "no divide instruction: EINVF32 estimate + two Newton steps (dependent 2p "
               "multiplies and subtracts), or the run-time library's FS$$DIV")),
    ("f_sqrt", ("float square root", 20, 30, "SPRAAN9",
                "no square-root instruction: EISQRTF32 estimate + Newton steps")),
    ("f_cmp", ("float compare feeding a branch (register)", 2, 2, "SPRUEO2",
               "CMPF32 RaH,RbH 1 + MOVST0 to copy the FPU flags to ST0 1; the branch is priced "
               "as a branch")),
    ("f_cmp_mem", ("float compare feeding a branch (memory operand)", 3, 3, "SPRUEO2",
                   "MOV32 RaH,mem32 + CMPF32 + MOVST0")),
    ("f_mask", ("float compare to a mask (branch-free select)", 1, 2, "SPRUEO2",
                "CMPF32 1; the select is one MOV32 RaH,RbH,cond (1)")),
    ("f_logic", ("float bit operation (sign, absolute value, select, zero)", 0, 1, "SPRUEO2",
                 "NEGF32/ABSF32/ZERO 1, or part of a select already priced")),
    ("f_move", ("float register move", 0, 1, "SPRUEO2", "MOV32 RaH,RbH 1, often none")),
    ("f_ldst", ("load or store of one value through an SSE register (a float, or an integer "
                "that gcc moves through one)", 1, 2, "SPRUEO2",
                "MOV32 RaH,mem32 / MOV32 mem32,RaH 1; +1 when a store waits for a 2p result")),
    ("f_ldst_packed", ("float load or store of 2 to 4 values", 2, 4, "SPRUEO2",
                       "one MOV32 per value (the FPU has no vector loads)")),
    ("f_packed", ("packed float arithmetic (2 to 4 lanes)", 2, 8, "SPRUEO2",
                  "one scalar 2p operation per lane: 2 lanes x 1 to 4 lanes x 2")),
    ("f_shuffle", ("packing or shuffling of float lanes", 0, 1, "model",
                   "exists only because gcc vectorised; scalar FPU code keeps the values in "
                   "separate registers")),
    ("f_cvt", ("int <-> float conversion", 2, 4, "SPRUEO2",
               "I32TOF32 / F32TOI32 (2p) + the move between CPU and FPU registers")),
    ("f_xfer", ("move between integer and SSE registers", 1, 4, "SPRUEO2",
                "MOV32 RaH,ACC / MOV32 ACC,RaH 1, plus pipeline alignment before the value is "
                "usable")),
])

JCC = re.compile(r"^j(n?[abgl]e?|n?[zesop]|n?[abgl]|[pn]e|po|rcxz|ecxz)$")
FLOAT_SCALAR = ("addss", "subss", "mulss", "minss", "maxss", "addsd", "subsd", "mulsd")
FLOAT_PACKED = ("addps", "subps", "mulps", "minps", "maxps", "addpd", "subpd", "mulpd")
SHUFFLE = ("shufps", "unpcklps", "unpckhps", "movlhps", "movhlps", "punpckldq", "punpcklqdq",
           "punpckhdq", "punpckhqdq", "pshufd", "insertps", "movshdup", "movsldup", "unpcklpd",
           "shufpd", "pshuflw", "pshufhw", "pinsrd", "pextrd", "pinsrq", "pextrq")
FLOAT_LOGIC = ("andps", "andnps", "orps", "xorps", "pxor", "pand", "pandn", "por", "andpd",
               "xorpd", "orpd", "andnpd")
CVT = ("cvtsi2ss", "cvtsi2ssl", "cvtsi2ssq", "cvttss2si", "cvtss2si", "cvttss2sil",
       "cvttss2siq", "cvtss2sd", "cvtsd2ss", "cvtsi2sdl", "cvtsi2sd", "cvttsd2si", "cvtdq2ps",
       "cvttps2dq", "cvtps2dq")


PREFIXES = ("cs", "ds", "data16", "rep", "repz", "repnz", "notrack", "bnd", "lock")


def _strip_suffix(m):
    """objdump -M suffix spells the operand size (movl, addq); returns (base, size in bits)."""
    sizes = {"b": 8, "w": 16, "l": 32, "q": 64}
    for base in ("cltq", "cqto", "cltd", "cwtl", "cbtw", "cwtd"):
        if m == base:
            return m, 64
    if m[-1] in sizes and len(m) > 2:
        return m[:-1], sizes[m[-1]]
    return m, 32


def _classify_float(m, ops):
    mem = "(" in ops
    if m in ("ucomiss", "comiss", "ucomisd", "comisd"):
        return "f_cmp_mem" if mem else "f_cmp"
    if m.startswith("cmp") and m.endswith(("ss", "ps", "sd", "pd")):
        return "f_mask"
    if m in FLOAT_SCALAR:
        return "f_arith_mem" if mem else "f_arith"
    if m in FLOAT_PACKED:
        return "f_packed"
    if m in ("divss", "divsd", "divps"):
        return "f_div"
    if m in ("sqrtss", "sqrtsd", "sqrtps", "rsqrtss"):
        return "f_sqrt"
    if m in SHUFFLE:
        return "f_shuffle"
    if m in FLOAT_LOGIC:
        return "f_logic"
    if m in CVT or m.startswith("cvt"):
        return "f_cvt"
    if m in ("movd", "movq") and "%xmm" in ops and not mem:
        return "f_xfer" if re.search(r"%[re]?[a-z0-9]+[dwb]?\b", ops.replace("%xmm", "")) \
            else "f_move"
    if m in ("movss", "movsd", "movd", "movq") and mem:
        return "f_ldst"
    if m in ("movups", "movaps", "movlps", "movhps", "movlpd", "movhpd", "movdqu", "movdqa"):
        return "f_ldst_packed" if mem else "f_move"
    if m in ("movss", "movsd"):
        return "f_move"
    return None


def _classify_int(m, ops):
    mem = "(" in ops
    base, bits = _strip_suffix(m)
    if JCC.match(m):
        return "jp" if m in ("jp", "jnp", "jpe", "jpo") else "jcc"
    if m in ("jmp", "jmpq"):
        return "jmp_ind" if "*" in ops else "jmp"
    if m in ("call", "callq"):
        return "call_ind" if "*" in ops else "call"
    if m in ("ret", "retq"):
        return "ret"
    if base in ("push", "pop"):
        return "push"
    if m.startswith("cmov"):
        return "cmov"
    if m.startswith("set"):
        return "setcc"
    if base in ("nop", "endbr64", "endbr32") or (base == "xchg" and ops in ("%ax,%ax", "%eax,%eax")):
        return "nop"
    if base in ("bsr", "lzcnt", "tzcnt", "bsf"):
        return "clz"
    if base in ("div", "idiv"):
        return "div64" if bits == 64 else "div32"
    if base in ("imul", "mul"):
        if ops.count(",") == 0:
            return "mulwide" if bits == 64 else "mul64"
        return "mul64" if bits == 64 else "mul32"
    if base in ("cmp", "test", "bt"):
        return "cmp64" if bits == 64 else "cmp"
    if base == "lea":
        return "lea"
    if base == "movabs":
        return "const64"
    if m in ("cltq", "cqto", "cltd", "cwtl", "cbtw", "cwtd") or \
            re.match(r"^mov[sz][bwl]?[bwlq]$", m) or m == "movslq":
        return "load" if mem else "mov"
    if base == "mov":
        if not mem:
            return "mov"
        if bits == 64:
            return "ldst64"
        return "store" if re.search(r",\s*-?[0-9a-fx]*\(", ops) else "load"
    if base in ("sar", "shr", "shl", "sal", "rol", "ror", "shrd", "shld"):
        return "shift64" if bits == 64 or base in ("shrd", "shld") else "shift"
    if base in ("add", "sub", "and", "or", "xor", "neg", "not", "inc", "dec", "adc", "sbb"):
        if mem:
            return "alu_mem"
        return "alu64" if bits == 64 else "alu"
    return None


def classify(mnemonic, operands):
    """The price class of one host instruction (None when the model does not know it)."""
    return _classify_float(mnemonic, operands) or _classify_int(mnemonic, operands)


def disassemble(binary):
    """{address: (mnemonic, operands, function)} of the binary's .text."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-M", "suffix", binary],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=True)
    dis = {}
    fn = None
    for line in out.stdout.splitlines():
        m = re.match(r"^([0-9a-f]+) <(.*)>:", line)
        if m:
            fn = m.group(2)
            continue
        m = re.match(r"^\s+([0-9a-f]+):\s+(.*)$", line)
        if m:
            words = m.group(2).split("#")[0].split(None, 1)
            while len(words) > 1 and words[0] in PREFIXES:  # cs nopw, data16 ..., rep stos
                words = words[1].split(None, 1)
            if words:
                dis[int(m.group(1), 16)] = (words[0], (words[1] if len(words) > 1 else "").strip(),
                                            fn)
    return dis


# Register families: every name of one x86-64 register (a write to the 32-bit name clears the
# upper half, so its value is a 32-bit one).
_FAMILIES = [("rax", "eax", "ax", "al"), ("rbx", "ebx", "bx", "bl"), ("rcx", "ecx", "cx", "cl"),
             ("rdx", "edx", "dx", "dl"), ("rsi", "esi", "si", "sil"), ("rdi", "edi", "di", "dil"),
             ("rbp", "ebp", "bp", "bpl"), ("rsp", "esp", "sp", "spl")] + \
    [("r%d" % n, "r%dd" % n, "r%dw" % n, "r%db" % n) for n in range(8, 16)]
_FAMILY = {name: fam[0] for fam in _FAMILIES for name in fam}
_REG32 = {fam[1] for fam in _FAMILIES}
_IMPLICIT = {"cltq": ("rax",), "cqto": ("rdx",), "cltd": ("rdx",)}
_SIGN_EXTEND_64 = ("movslq", "movswq", "movsbq", "cltq")


def _operands(ops):
    """AT&T operands split at the commas outside parentheses."""
    out, depth, cur = [], 0, ""
    for ch in ops:
        depth += (ch == "(") - (ch == ")")
        if ch == "," and depth == 0:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def _written_family(mnem, ops):
    """The register family an instruction writes (its last operand, or an implicit one)."""
    if mnem in _IMPLICIT:
        return _IMPLICIT[mnem][0]
    if mnem.startswith(("cmp", "test", "push", "j", "bt", "ucomis", "comis")):
        return None
    last = _operands(ops)[-1:] or [""]
    return _FAMILY.get(last[0].lstrip("%")) if last[0].startswith("%") else None


def _immediate(operand):
    """The value of an AT&T immediate ($0x..), objdump's 64-bit spelling of negatives undone."""
    v = int(operand[1:], 0)
    return v - 2 ** 64 if v >= 2 ** 63 else v


def _narrow_writer(mnem, ops):
    """True when the value this writer leaves in its destination is a 32-bit one."""
    if mnem in _SIGN_EXTEND_64:
        return True
    operands = _operands(ops)
    dest = operands[-1] if operands else ""
    if dest.lstrip("%") in _REG32:
        return True  # a 32-bit write clears the upper half
    if mnem == "movq" and operands and operands[0].startswith("$"):
        return -2 ** 31 <= _immediate(operands[0]) < 2 ** 31
    return False


def _stack_slot(operand):
    """A frame slot addressed from %rsp (its offset), else None."""
    m = re.match(r"^(-?0x[0-9a-f]+|-?[0-9]+)?\(%rsp\)$", operand)
    if not m:
        return None
    return int(m.group(1) or "0", 0)


def _shift_leaves_narrow(mnem, ops):
    """A 64-bit right shift by 32 or more leaves a 32-bit value."""
    if mnem not in ("sarq", "shrq") or not ops.startswith("$"):
        return False
    return _immediate(_operands(ops)[0]) >= 32


_MULTI_WRITERS = ("xchg", "xadd", "cmpxchg")  # write every register operand (cmpxchg: rax too)
_STRING_OPS = tuple(op + w for op in ("stos", "lods", "scas", "cmps") for w in "bwlq")
_BIT_WRITERS = ("bts", "btr", "btc")
_SSE_STORE_BYTES = {"movss": 4, "movd": 4, "movsd": 8, "movlps": 8, "movhps": 8, "movlpd": 8,
                    "movhpd": 8, "movaps": 16, "movups": 16, "movapd": 16, "movupd": 16,
                    "movdqa": 16, "movdqu": 16}


def _store_bytes(mnem, operands):
    """Bytes an instruction writes to its memory destination (8 when unsure: the most a slot
    holds; a 16-byte SSE store its 16)."""
    if mnem in _SSE_STORE_BYTES:
        return _SSE_STORE_BYTES[mnem]
    if mnem == "movq" and operands and operands[0].startswith("%xmm"):
        return 8
    return {"b": 1, "w": 2, "l": 4, "q": 8}.get(mnem[-1:], 8)


def _frame_store(out, mnem, operands, state):
    """A store into the frame: every tracked slot it overlaps forgotten; an 8-byte copy of a
    value shown 32-bit tracked. A store into the frame addressed otherwise forgets them all."""
    dest = operands[-1]
    slot = _stack_slot(dest)
    if slot is None:
        return {r for r in out if not isinstance(r, int)}
    width = _store_bytes(mnem, operands)
    out = {r for r in out if not isinstance(r, int) or r + 8 <= slot or r >= slot + width}
    if mnem == "movq" and _FAMILY.get(operands[0].lstrip("%")) in state:
        out.add(slot)
    return out


def _transfer(state, mnem, ops, track_slots=True):
    """The set of narrow locations (register families, frame slots) after one instruction."""
    operands = _operands(ops)
    out = set(state)
    if mnem in ("call", "callq"):
        return {r for r in out if r in _CALLEE_SAVED}
    if mnem.startswith(("push", "pop", "leave", "ret")):  # %rsp moves: the slots' offsets too
        out = {r for r in out if not isinstance(r, int)}
    string_op = mnem in _STRING_OPS or "%es:" in ops  # movs with -M suffix: movsq %ds:..,%es:..
    if mnem.startswith(_MULTI_WRITERS + _BIT_WRITERS) or string_op:
        written = {_FAMILY.get(o.lstrip("%")) for o in operands if o.startswith("%")}
        if mnem.startswith("cmpxchg") or string_op:
            written |= {"rax", "rcx", "rdi", "rsi"}
        out = {r for r in out if r not in written and not isinstance(r, int)}
        return out  # the frame forgotten too: a string op or a memory operand may write it
    if mnem.startswith(("imul", "mul", "div", "idiv")) and len(operands) < 2:
        return out - {"rax", "rdx"}
    fam = _written_family(mnem, ops)
    if fam == "rsp":
        return {r for r in out if not isinstance(r, int)}
    if fam is not None:
        src = operands[0] if operands else ""
        copy = mnem == "movq" and len(operands) == 2
        narrow = _narrow_writer(mnem, ops) or _shift_leaves_narrow(mnem, ops) or \
            (copy and _FAMILY.get(src.lstrip("%")) in state) or \
            (copy and _stack_slot(src) in state)
        out.discard(fam)
        if narrow:
            out.add(fam)
        return out
    if operands and "(%rsp" in operands[-1] and not mnem.startswith(_NO_WRITE):
        out = _frame_store(out, mnem, operands, state)
        if not track_slots:
            out = {r for r in out if not isinstance(r, int)}
    return out


_NO_WRITE = ("cmp", "test", "bt", "ucomis", "comis", "j", "push", "nop", "prefetch")
_CALLEE_SAVED = {"rbx", "rbp", "r12", "r13", "r14", "r15"}


def _frame_escapes(dis, addrs):
    """The frame's address leaves %rsp (a lea of a slot, a copy of %rsp, an indexed slot): a
    store through another register may then write a slot, so none is tracked."""
    for a in addrs:
        mnem, ops, _ = dis[a]
        for o in _operands(ops):
            if "%rsp" not in o:
                continue
            if _stack_slot(o) is None and o != "%rsp":
                return True
            if o == "%rsp" and not mnem.startswith(("add", "sub", "and", "push", "pop")):
                return True
            if mnem.startswith("lea") and _stack_slot(o) is not None:
                return True
    return False


class Blocks:
    """Which registers hold a value shown 32-bit before each instruction: a forward data-flow
    over each function's control flow (a 32-bit write, a sign extension, a 32-bit immediate, a
    right shift by 32 or more, copies of those through registers and, where the frame's address
    never escapes, frame slots; a call keeps only the callee-saved registers; where paths join,
    what holds on all of them). A function with an indirect jump (its targets unknown here) is
    left without any: every operand of it is priced wide, as is every instruction that only a
    jump from another function (a .cold part's) reaches."""

    def __init__(self, dis):
        self.dis = dis
        self.order = sorted(dis)
        self.narrow_before = {}
        by_fn = collections.defaultdict(list)
        for addr in self.order:
            by_fn[dis[addr][2]].append(addr)
        for addrs in by_fn.values():
            if any(dis[a][0].startswith("jmp") and dis[a][1].startswith("*") for a in addrs):
                continue
            self._solve(addrs, not _frame_escapes(dis, addrs))

    def _successors(self, addrs, i):
        mnem, ops, _ = self.dis[addrs[i]]
        succ = []
        if mnem.startswith("j") and not ops.startswith("*"):
            try:
                succ.append(int(ops.split()[0], 16))
            except ValueError:
                pass
        if mnem not in ("jmp", "jmpq", "ret", "retq") and i + 1 < len(addrs):
            succ.append(addrs[i + 1])
        return succ

    def _solve(self, addrs, track_slots):
        inside = set(addrs)
        pos = {a: i for i, a in enumerate(addrs)}
        state = {addrs[0]: frozenset()}
        work = [addrs[0]]
        while work:
            a = work.pop()
            mnem, ops, _ = self.dis[a]
            out = frozenset(_transfer(state[a], mnem, ops, track_slots))
            for nxt in self._successors(addrs, pos[a]):
                if nxt not in inside:
                    continue
                old = state.get(nxt)
                new = out if old is None else (old & out)
                if new != old:
                    state[nxt] = new
                    work.append(nxt)
        self.narrow_before.update(state)


_BLOCKS_CACHE = []


def _blocks_of(dis):
    """Blocks of dis, built once per disassembly (price runs once per function and config)."""
    if not _BLOCKS_CACHE or _BLOCKS_CACHE[0][0] is not dis:
        _BLOCKS_CACHE[:] = [(dis, Blocks(dis))]
    return _BLOCKS_CACHE[0][1]


def narrow_product(addr, dis, blocks):
    """True when a 64-bit imul multiplies two values shown 32-bit where it executes."""
    _, ops, _ = dis[addr]
    operands = _operands(ops)
    sources = operands[:2] if len(operands) == 3 else operands
    state = blocks.narrow_before.get(addr, frozenset())
    for src in sources:
        if src.startswith("$"):
            continue  # an imm32, sign-extended
        if _FAMILY.get(src.lstrip("%")) not in state and _stack_slot(src) not in state:
            return False
    return True


def _position(token, last):
    if token.startswith("0x"):
        return int(token, 16)
    if token[0] in "+-":
        return last + int(token)
    if token == "*":
        return last
    return int(token)


def parse_dump(path, object_name):
    """Executed count and taken count per instruction address of the object whose path ends in
    object_name, from one callgrind dump written with --dump-instr=yes --collect-jumps=yes.
    Returns ({address: count}, {address: taken}, summary Ir)."""
    counts = collections.Counter()
    taken = collections.Counter()
    last = 0
    in_obj = False
    objects = {}
    skip_next = False
    jump = None
    summary = 0
    with open(path) as f:
        for line in f:
            if line.startswith(("ob=", "cob=")):
                m = re.match(r"c?ob=\((\d+)\)\s*(.*)", line.strip())
                if m.group(2):
                    objects[m.group(1)] = m.group(2)
                if line.startswith("ob="):
                    in_obj = objects.get(m.group(1), "").endswith(object_name)
            elif line.startswith("summary:"):
                summary = int(line.split()[1])
            elif line.startswith("calls="):
                skip_next = True
            elif line.startswith("jcnd="):
                jump = int(line[5:].split("/")[0])
            elif line.startswith("jump="):
                jump = 0
            elif line[:1] in "0123456789+-*" and line.strip():
                fields = line.split()
                last = _position(fields[0], last)
                if skip_next:
                    skip_next = False
                elif jump is not None:
                    if in_obj:
                        taken[last] += jump
                    jump = None
                elif len(fields) >= 3 and in_obj:
                    counts[last] += int(fields[2])
    return counts, taken, summary


def price(counts, taken, dis, exclude=("bench_", "flt_bench_")):
    """Per class: [host instructions, low cycles, high cycles]; functions whose name starts with
    one of exclude (the replay harness) are left out. Raises ValueError on an instruction the
    model has no class for."""
    per_class = collections.OrderedDict((k, [0, 0, 0]) for k in PRICES)
    unknown = collections.Counter()
    blocks = _blocks_of(dis)
    for addr, n in counts.items():
        if addr not in dis:
            unknown["<no disassembly at 0x%x>" % addr] += n
            continue
        mnem, ops, fn = dis[addr]
        if fn and fn.startswith(exclude):
            continue
        cls = classify(mnem, ops)
        if cls is None:
            unknown[mnem] += n
            continue
        if cls == "mul64" and narrow_product(addr, dis, blocks):
            cls = "mul32x32"
        if cls == "jcc":
            t = min(taken.get(addr, 0), n)
            _add(per_class, "jcc_taken", t)
            _add(per_class, "jcc_not", n - t)
        else:
            _add(per_class, cls, n)
    if unknown:
        raise ValueError("no price class for: " + ", ".join(
            "%s (%d)" % kv for kv in unknown.most_common()))
    return per_class


def _add(per_class, cls, n):
    _, lo, hi, _, _ = PRICES[cls]
    row = per_class[cls]
    row[0] += n
    row[1] += n * lo
    row[2] += n * hi


def totals(per_class):
    """(host instructions, low cycles, high cycles) over every class."""
    return tuple(sum(r[i] for r in per_class.values()) for i in range(3))


def function_cost(counts, taken, dis, function):
    """Priced cost of one call of a function that is not inlined: its own instructions (the
    callees it calls are priced with it), per call, plus the call itself; calls counted at the
    entry instruction. Returns (calls, host instructions, low, high) per call."""
    entry = min(a for a, v in dis.items() if v[2] == function)
    calls = counts.get(entry, 0)
    if calls == 0:
        return 0, 0, 0, 0
    mine = {a: n for a, n in counts.items() if a in dis and dis[a][2] == function}
    host, lo, hi = totals(price(mine, taken, dis))
    _, clo, chi, _, _ = PRICES["call"]
    return calls, host / calls, lo / calls + clo, hi / calls + chi


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("dump")
    ap.add_argument("--points", type=int, default=1)
    a = ap.parse_args()
    dis = disassemble(a.binary)
    counts, taken, _ = parse_dump(a.dump, a.binary.rsplit("/", 1)[-1])
    per_class = price(counts, taken, dis)
    for k, (n, lo, hi) in per_class.items():
        if n:
            print("%-14s %9.1f %9.1f %9.1f" % (k, n / a.points, lo / a.points, hi / a.points))
    n, lo, hi = totals(per_class)
    print("total %.1f host, cycles [%.0f, %.0f], us [%.2f, %.2f]" % (
        n / a.points, lo / a.points, hi / a.points, lo / a.points / 150, hi / a.points / 150))


if __name__ == "__main__":
    sys.exit(main())
