#!/usr/bin/env python3
"""tools/ram_budget.py: every function the control interrupt can reach must be placed in RAM by
the linker file (as the build's preprocessor macros leave it), except what the build leaves in
flash on purpose; and the RAM blocks must keep their margin. Runs the tool on objects the host
gcc builds from a small program (the same section and call-graph formats as the Arm proxy)."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "ram_budget.py")

PROGRAM = """
volatile int v;
static void step(void) { v = v * 3 + 1; }
void search(void) { %s }
void table_owner(int k);
void control(int k) { step(); if (k) search(); }
F28335_RAMFUNC(fw_adc_isr)
void fw_adc_isr(void) { control(v); }
int main(void) { fw_adc_isr(); return 0; }
"""

LINKER = """
MEMORY
{
PAGE 0 :
   RAML0L3    : origin = 0x008000, length = 0x%X
   FLASHD     : origin = 0x320000, length = 0x008000
PAGE 1 :
   RAML4L7    : origin = 0x00C000, length = 0x004000
}
SECTIONS
{
   ramfuncs   : {
                   *(ramfuncs)
                   %s %s
#ifndef SIXPHASE_FW_Q24
                   *(.text:_search)
#endif
                   -lrts2800_fpu32.lib(.text)
                }
                LOAD = FLASHD,
                RUN = RAML0L3,
                PAGE = 0
   ramconsts  : {
                   *prog.*obj(.econst)
                }
                LOAD = FLASHD,
                RUN = RAML4L7,
                PAGE = 1
   .ebss      : > RAML4L7, PAGE = 1
}
"""


@unittest.skipUnless(shutil.which("gcc") and shutil.which("size"), "needs gcc and binutils")
class RamBudget(unittest.TestCase):
    def run_tool(self, listed_step, ram_words=0x4000, q24=False, from_flash="",
                 control_entry="*(.text:_control)"):
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "prog.c")
            with open(src, "w") as f:
                f.write("#define F28335_RAMFUNC(fn)\n" + PROGRAM % "v = 2;")
            for sub, flags in (("o2", ["-ffunction-sections", "-fcallgraph-info=su"]),
                               ("noinline", ["-fno-inline", "-fcallgraph-info"])):
                os.mkdir(os.path.join(d, sub))
                subprocess.run(["gcc", "-O2"] + flags + ["-c", src, "-o",
                                os.path.join(d, sub, "prog.o")], cwd=os.path.join(d, sub),
                               check=True)
            cmd = os.path.join(d, "link.cmd")
            with open(cmd, "w") as f:
                f.write(LINKER % (ram_words, control_entry,
                                  "*(.text:_step)" if listed_step else ""))
            args = [sys.executable, TOOL, "--linker", cmd, "--objects", os.path.join(d, "o2"),
                    "--callgraph", os.path.join(d, "noinline"), "--size", "size"]
            if q24:
                args += ["--define", "SIXPHASE_FW_Q24=1"]
            if from_flash:
                args += ["--from-flash", from_flash]
            return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  text=True)

    def test_everything_of_the_period_in_ram_passes(self):
        r = self.run_tool(listed_step=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("per-period path: 4 functions, all in ramfuncs", r.stdout)

    def test_a_static_helper_left_in_flash_fails(self):
        r = self.run_tool(listed_step=False)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("step runs in the control interrupt but from flash: add "
                      "`*(.text:_step)`", r.stderr)

    def test_q24_branch_leaves_the_search_in_flash(self):
        r = self.run_tool(listed_step=True, q24=True, from_flash="search")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("in flash on purpose: search", r.stdout)
        # the preprocessor drops the search from ramfuncs: unless the build says so, a failure
        r = self.run_tool(listed_step=True, q24=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("search runs in the control interrupt but from flash", r.stderr)
        # and a function both listed and named in flash is a contradiction
        r = self.run_tool(listed_step=True, from_flash="search")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("search is listed in ramfuncs and named --from-flash", r.stderr)

    def test_an_entry_for_one_object_counts_that_objects_copy(self):
        # *OBJECT.*obj(.text:_NAME): placed for the path, measured in that object only
        def code_bytes(r):
            self.assertEqual(r.returncode, 0, r.stderr)
            line = [l for l in r.stdout.splitlines() if l.startswith("| ramfuncs")][0]
            return int(line.split("|")[2])
        everywhere = code_bytes(self.run_tool(listed_step=True))
        here = code_bytes(self.run_tool(listed_step=True,
                                        control_entry="*prog.*obj(.text:_control)"))
        elsewhere = code_bytes(self.run_tool(listed_step=True,
                                             control_entry="*other.*obj(.text:_control)"))
        self.assertEqual(here, everywhere)
        self.assertLess(elsewhere, here)

    def test_a_full_block_fails(self):
        # 1024 words of library reserve alone fill more than 90 % of 0x460 words
        r = self.run_tool(listed_step=True, ram_words=0x460)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("RAML0L3 needs", r.stderr)


if __name__ == "__main__":
    unittest.main()
