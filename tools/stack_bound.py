#!/usr/bin/env python3
"""An upper bound of the F28335 image's stack, in C28x words, from register-poor proxy builds
(tools/check_stack_bound.sh builds them).

usage: stack_bound.py --background ROOT --isr ROOT --stack-words N [--min-free F]
                      [--summary FILE.json] BUILD_DIR...

Each BUILD_DIR is one build of the image's sources (for example -O2, and -O2 -fno-inline) with
one subdirectory per proxy:
  m0/   arm-none-eabi-gcc -mcpu=cortex-m0 -mthumb -fcallgraph-info=su: the call graph
        (*.ci, indirect calls resolved by tools/stack_depth.py's `indirect-call:` notes)
        and the Cortex-M0's frames;
  avr/  avr-gcc -mmcu=atmega1284p -fstack-usage (*.su): the AVR's frames;
  x86/  gcc -m32 -mpreferred-stack-boundary=2 -maccumulate-outgoing-args -fstack-usage
        (*.su): the i386's frames (4-byte stack alignment, the C28x's 2 words; gcc's default
        16 would pad every frame).
The proxies' frames are matched to the graph by function name (gcc clones such as
NAME.isra.0 go by the C name; a static function by its name).

The bound of one build is
  deepest background path from ROOT (main)  +  deepest control-interrupt path (fw_adc_isr)
  +  the interrupt context,
the interrupt nested on top of the background's deepest point. The image's bound is the
largest over the builds (the compiler may inline like gcc -O2 or not at all). Recursion, a
dynamic (unbounded) frame, an indirect call no note resolves and a called routine that is
neither compiled here nor a known run-time or ROM routine are refused.

Frame of a compiled function, in C28x words: the LARGEST over the proxies of
  even(ceil(bytes / 2))  +  CALL_WORDS
- bytes / 2: a C28x word is 16 bits. Every object a C28x frame holds takes at least as many
  bytes on the Cortex-M0 and the i386 (int 4 bytes against 1 word, pointers and 32-bit values
  4 bytes = 2 words, 64-bit values 8 bytes = 4 words, their alignment no smaller), provided no
  object is narrower than 16 bits on the proxy: the image has no `char` data, and bool (1 byte
  on the proxies, 16 bits on the C28x) is compiled as unsigned short for this measurement
  (BOOL_FLAGS). The i386 passes every argument on the stack (4 bytes or more each), so its
  frames also hold what the C28x passes on the stack beyond its argument registers. The AVR
  has 16-bit int like the C28x but 16-bit pointers (2 words on the C28x): its frames are not
  a bound where they hold pointers, and need not be; the largest of the three is a bound when
  one of them is, and the AVR (8-bit registers: 32-bit values spill early) only raises it.
- even(): the C28x keeps 32-bit data at even addresses; a frame is rounded up to even words.
- CALL_WORDS per function, what the C28x adds that a proxy frame may not hold: the return
  address the call pushes (LCR: 2 words) and the whole save-on-entry set (XAR1, XAR2, XAR3: 6
  words; R4H..R7H with fpu32: 8 words; TI SPRU514, "Register Use and Preservation"), whether
  or not the function uses them.
Called routines that are not compiled here get an allowance, or nothing when the F28335 does
the work in instructions (INSTRUCTIONS: with fpu32, float addition, subtraction,
multiplication, comparison and conversion are FPU instructions, TI SPRU514 --float_support;
double is float under COFF; float division is a library call and gets the allowance):
- RTS_WORDS for each run-time library helper a path calls (gcc's __aeabi_* / __*di3 and
  memcpy / memset stand for TI's rts2800_fpu32.lib routines: division, 64-bit arithmetic,
  copies). TI's library is not available here, so this is an allowance, not a measurement:
  2 words of return address, the save-on-entry set (14) and 16 words of working data (a
  64-bit division's operands, quotient and remainder), twice, since one helper may call
  another (signed 64-bit division calls the unsigned one).
- ADC_CAL_WORDS for TI's ADC_cal (boot ROM / OTP at 0x380080, called through a pointer at
  start-up): a 9-word leaf that writes two trim registers; its return address (2 words) plus
  2 words of any register it might push, doubled for margin.
The interrupt context, CONTEXT below (TI SPRU430, "Interrupt ... Standard Operation": the CPU
saves 14 words with 32-bit pushes, after aligning the stack; TI SPRU514, "Interrupt
Handling": an interrupt routine that calls functions saves every save-on-call register, with
fpu32 also STF and RB).
"""
import argparse
import glob
import json
import math
import os
import re
import sys

import stack_depth

GRAPH_PROXY = "m0"
PROXIES = ("m0", "avr", "x86")
# bool as the C28x holds it (16 bits) in every proxy build: gcc's stdbool.h is skipped.
BOOL_FLAGS = "-D_STDBOOL_H -Dbool=__UINT16_TYPE__ -Dtrue=1 -Dfalse=0"
CALL_WORDS = 2 + 6 + 8    # return address + XAR1..XAR3 + R4H..R7H
RTS_WORDS = 2 * (2 + 14 + 16)
ADC_CAL_WORDS = 2 * (2 + 2)
ROM_ROUTINES = {"ADC_cal": ADC_CAL_WORDS}
RTS = re.compile(r"^(__aeabi_\w+|__\w+[sdt][ifx]\d|mem(cpy|set|move))$")
# What the F28335 does in instructions where a proxy calls a helper (no call, nothing counted):
# 32-bit float arithmetic, comparisons and conversions but division (fpu32; double is float
# under COFF, so gcc's double helpers are float ones there), and Thumb-1's switch helpers.
INSTRUCTIONS = re.compile(r"^(__aeabi_([fd](add|sub|rsub|mul|cmp\w*|2iz|2uiz|2f|2d)|[u]?i2[fd])"
                          r"|__gnu_thumb1_case_\w+)$")
CONTEXT = [
    ("CPU automatic save: T:ST0, AH:AL, PH:PL, AR1:AR0, DP:ST1, DBGSTAT:IER, PC "
     "(SPRU430)", 14),
    ("stack alignment before the automatic save (SP + 1, 32-bit pushes at even addresses)", 2),
    ("interrupt prologue, save-on-call and save-on-entry CPU registers: AR1H:AR0H, "
     "XAR2..XAR7, XT (SPRU514)", 16),
    ("interrupt prologue: RPC (the routine calls functions)", 2),
    ("interrupt prologue, fpu32: R0H..R7H", 16),
    ("interrupt prologue, fpu32: STF and RB", 4),
    ("interrupt prologue: frame alignment (ASP)", 2),
]
SU_LINE = re.compile(r"^(.*):(\S+)\t(\d+)\t(\S+)\s*$")


def fail(msg):
    sys.stderr.write("stack_bound: %s\n" % msg)
    sys.exit(1)


def words(nbytes):
    """Proxy bytes as C28x words: half, rounded up to an even count (see the docstring)."""
    w = (nbytes + 1) // 2
    return w + (w & 1)


def read_su(directory):
    """{C name: largest frame in bytes} of a proxy's -fstack-usage files."""
    frames = {}
    paths = sorted(glob.glob(os.path.join(directory, "*.su")))
    if not paths:
        fail("%s: no .su files" % directory)
    for path in paths:
        for n, line in enumerate(open(path), 1):
            m = SU_LINE.match(line.rstrip("\n"))
            if not m:
                fail("%s:%d: not a stack-usage line" % (path, n))
            name, size, kind = stack_depth.c_name(m.group(2)), int(m.group(3)), m.group(4)
            if kind not in ("static", "dynamic,bounded"):
                fail("%s: %s has a %s frame (no bound)" % (path, name, kind))
            frames[name] = max(frames.get(name, 0), size)
    return frames


def read_build(directory):
    """The call graph (indirect calls resolved) and {proxy: {name: bytes}} of one build."""
    cis = sorted(glob.glob(os.path.join(directory, GRAPH_PROXY, "*.ci")))
    if not cis:
        fail("%s: no %s/*.ci call graph" % (directory, GRAPH_PROXY))
    frames, edges, sites, sources, defined = stack_depth.load_raw(cis)
    stack_depth.resolve(defined, edges, sites, sources)
    proxy_frames = {GRAPH_PROXY: frames}
    for proxy in PROXIES:
        if proxy != GRAPH_PROXY and os.path.isdir(os.path.join(directory, proxy)):
            proxy_frames[proxy] = read_su(os.path.join(directory, proxy))
    if len(proxy_frames) < 2:
        fail("%s: frames of at least two proxies are needed" % directory)
    return edges, defined, proxy_frames


def frame_words(name, defined, proxy_frames):
    """(words, which): a compiled function's bound or a routine's allowance."""
    if name in defined:
        best = (-1, "")
        for proxy, frames in sorted(proxy_frames.items()):
            size = frames.get(name if proxy == GRAPH_PROXY else stack_depth.c_name(name))
            if size is not None and words(size) > best[0]:
                best = (words(size), proxy)
        if best[0] < 0:
            fail("%s: no frame measured" % name)
        return best[0] + CALL_WORDS, best[1]
    if name in ROM_ROUTINES:
        return ROM_ROUTINES[name], "ROM allowance"
    if INSTRUCTIONS.match(name):
        return 0, "an instruction on the C28x"
    if RTS.match(name):
        return RTS_WORDS, "run-time library allowance"
    fail("%s is called but neither compiled here nor a known run-time or ROM routine" % name)


class Bound:
    def __init__(self, edges, defined, proxy_frames):
        self.edges, self.defined, self.proxy_frames = edges, defined, proxy_frames
        self.memo = {}

    def deepest(self, fn, stack=()):
        """(words, [(name, words, which)...]) of the deepest path from fn."""
        if fn in stack:
            fail("recursion through %s (no bound)" % " -> ".join(stack + (fn,)))
        if fn not in self.memo:
            own, which = frame_words(fn, self.defined, self.proxy_frames)
            best = (0, [])
            for callee in sorted(self.edges.get(fn, ())):
                d = self.deepest(callee, stack + (fn,))
                if d[0] > best[0]:
                    best = d
            self.memo[fn] = (own + best[0], [(fn, own, which)] + best[1])
        return self.memo[fn]

    def root(self, fn):
        if fn not in self.defined:
            fail("root %s not found" % fn)
        return self.deepest(fn)


def bound_of(directory, background, isr):
    bound = Bound(*read_build(directory))
    bg, isr_d = bound.root(background), bound.root(isr)
    context = sum(w for _, w in CONTEXT)
    return {"build": os.path.basename(os.path.normpath(directory)),
            "background_words": bg[0], "isr_words": isr_d[0], "context_words": context,
            "bound_words": bg[0] + isr_d[0] + context,
            "background_path": ["%s (%d, %s)" % p for p in bg[1]],
            "isr_path": ["%s (%d, %s)" % p for p in isr_d[1]]}


class Arguments(argparse.ArgumentParser):
    def error(self, message):
        fail(message)  # one line, non-zero exit


def main():
    ap = Arguments(description=__doc__.split("\n")[0])
    ap.add_argument("--background", required=True)
    ap.add_argument("--isr", required=True)
    ap.add_argument("--stack-words", type=int, required=True)
    ap.add_argument("--min-free", type=float, default=0.20,
                    help="share of the linked stack the bound must leave (default 0.20)")
    ap.add_argument("--summary", help="write the figures as JSON")
    ap.add_argument("builds", nargs="+")
    a = ap.parse_args()
    if a.stack_words <= 0 or not 0.0 <= a.min_free < 1.0:
        fail("--stack-words must be positive and --min-free within 0..1")
    for d in a.builds:
        if not os.path.isdir(d):
            fail("%s is not a directory" % d)
    results = [bound_of(d, a.background, a.isr) for d in a.builds]
    worst = max(results, key=lambda r: r["bound_words"])
    allowed = int(math.floor(a.stack_words * (1.0 - a.min_free)))
    free = 1.0 - float(worst["bound_words"]) / a.stack_words
    for r in results:
        print("%s: background %d + interrupt %d + context %d = %d words" % (
            r["build"], r["background_words"], r["isr_words"], r["context_words"],
            r["bound_words"]))
    print("background path (%s): %s" % (worst["build"], " -> ".join(worst["background_path"])))
    print("interrupt path (%s): %s" % (worst["build"], " -> ".join(worst["isr_path"])))
    print("stack bound %d of %d words (%.0f %% left; at least %.0f %% must be: %d words)" % (
        worst["bound_words"], a.stack_words, 100.0 * free, 100.0 * a.min_free, allowed))
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump({"bound_words": worst["bound_words"], "stack_words": a.stack_words,
                       "free_percent": round(100.0 * free, 1), "min_free": a.min_free,
                       "worst_build": worst["build"], "builds": results,
                       "context": CONTEXT, "call_words": CALL_WORDS, "rts_words": RTS_WORDS,
                       "rom_words": ROM_ROUTINES}, f, indent=1)
    if worst["bound_words"] > allowed:
        fail("the bound, %d words, leaves less than %.0f %% of the %d-word stack (at most %d)"
             % (worst["bound_words"], 100.0 * a.min_free, a.stack_words, allowed))


if __name__ == "__main__":
    main()
