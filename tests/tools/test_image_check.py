#!/usr/bin/env python3
"""tools/image_check.py, the model of TI's linker, on the firmware's own proxy build: today's
linker file passes for both images, and each defect the check exists for is caught - the flash
linker file and the RAM linker file as they were before issue 22 (fixtures/), the run-time
library's whole `.text` in RAM, a misspelt function, a missing jump-table rule, a missing
library member, an unmarked period function and a marked function the period never calls."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "image_check.py")
CMD = os.path.join(ROOT, "firmware", "f28335", "F28335_flash.cmd")
ASM = os.path.join(ROOT, "firmware", "f28335", "codestart.asm")
FIXTURES = os.path.join(HERE, "fixtures")
FLASH_LIST = os.path.join(ROOT, "tools", "flash_on_purpose.txt")





@unittest.skipUnless(shutil.which("arm-none-eabi-gcc"), "needs arm-none-eabi-gcc")
class ImageCheck(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp()
        cls.build = os.path.join(cls.work, "proxy")
        done = subprocess.run(["bash", os.path.join(ROOT, "tools", "check_target_memory.sh"),
                               cls.build], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True)
        cls.build_output = done.stdout
        cls.build_status = done.returncode

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def run_tool(self, linker_text=None, linker=CMD, arith="float", objects="o2",
                 from_flash="", defines=()):
        if linker_text is not None:
            linker = os.path.join(self.work, "variant.cmd")
            with open(linker, "w") as f:
                f.write(linker_text)
        args = [sys.executable, TOOL, "--linker", linker,
                "--objects", os.path.join(self.build, arith, objects),
                "--callgraph", os.path.join(self.build, arith, "m0"), "--asm", ASM,
                "--stack-words", "1792", "--from-flash-file", FLASH_LIST,
                "--from-flash", from_flash]
        for d in defines:
            args += ["--define", d]
        done = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        return done.returncode, done.stderr

    def variant(self, old, new):
        text = open(CMD).read()
        self.assertIn(old, text)
        return text.replace(old, new)

    def test_todays_linker_file_passes_both_images(self):
        self.assertEqual(self.build_status, 0, self.build_output[-3000:])
        self.assertEqual(self.run_tool(), (0, ""))
        self.assertEqual(self.run_tool(arith="fixed", defines=["SIXPHASE_FW_Q24=1"]), (0, ""))

    def test_flash_file_before_issue_22_does_not_boot(self):
        status, err = self.run_tool(
            linker=os.path.join(FIXTURES, "F28335_flash_before_issue22.cmd"))
        self.assertEqual(status, 1)
        self.assertRegex(err, r"boot: _c_int00 \(rts2800_fpu32\.lib<boot28\.asm\.obj>\(\.text\)\)"
                              r" runs before the RAM copy but is linked to run at RAML0L3")
        self.assertIn("boot: _args_main", err)
        # and its constant tables' LOAD and RUN ranges were on different pages
        self.assertIn("ramconsts: memory range FLASHA is not on PAGE 1", err)

    def test_whole_library_text_in_ram_does_not_boot(self):
        text = re.sub(r"-l rts2800_fpu32\.lib<[^>]*>\(\.text\)", "-lrts2800_fpu32.lib(.text)",
                      open(CMD).read())
        status, err = self.run_tool(text)
        self.assertEqual(status, 1)
        self.assertIn("boot: _c_int00", err)
        self.assertIn("run-time library: rts2800_fpu32.lib<exit.c.obj>(.text) runs from RAM "
                      "but the period never calls it", err)

    def test_ram_file_before_issue_22_overflows(self):
        status, err = self.run_tool(
            linker=os.path.join(FIXTURES, "F28335_ram_before_issue22.cmd"))
        self.assertEqual(status, 1)
        self.assertRegex(err, r"memory range RAML0L3 overflows: \d+ of 16384 words")

    def test_misspelt_function_takes_nothing(self):
        status, err = self.run_tool(self.variant("*(.TI.ramfunc)",
                                                 "*(.TI.ramfunc) *(.text:_ctl_stepp)"))
        self.assertEqual(status, 1)
        self.assertIn("`*(.text:_ctl_stepp)` takes nothing", err)

    def test_jump_tables_of_the_period_must_be_in_ram(self):
        status, err = self.run_tool(self.variant("*drive.*obj(.switch)", ""))
        self.assertEqual(status, 1)
        self.assertIn("jump tables: drive.c.obj(.switch) run from flash but drive_control_step "
                      "(period) has a switch", err)

    def test_library_routine_of_the_period_must_be_in_ram(self):
        status, err = self.run_tool(self.variant("<i_div28.asm.obj l_div28.asm.obj>(.text)\n#endif",
                                                 "<i_div28.asm.obj>(.text)\n#endif"))
        self.assertEqual(status, 1)
        self.assertIn("the period calls rts2800_fpu32.lib<l_div28.asm.obj>(.text)", err)

    def test_q24_link_without_its_define_is_caught(self):
        status, err = self.run_tool(arith="fixed")
        self.assertEqual(status, 1)
        self.assertIn("the period calls rts2800_fpu32.lib<ll_mpy28.asm.obj>(.text)", err)

    def test_unmarked_period_function_is_caught(self):
        # the no-inline proxy objects carry no placement marks: every function is in .text
        status, err = self.run_tool(objects="noinline")
        self.assertEqual(status, 1)
        self.assertIn("period: drive_control_isr runs in the control interrupt from flash "
                      "(drive.c.obj(.text", err)

    def test_marked_function_outside_the_period_is_caught(self):
        status, err = self.run_tool(from_flash="ctl_step")
        self.assertEqual(status, 1)
        self.assertIn("period: ctl_step runs from RAM (ctl_step.c.obj(.TI.ramfunc)) but the "
                      "control period never calls it", err)

    def test_section_no_rule_takes(self):
        status, err = self.run_tool(self.variant("   .switch    : > FLASHA,  PAGE = 0\n", ""))
        self.assertEqual(status, 1)
        self.assertIn("commission.c.obj(.switch) matches no rule of the linker file", err)

    def test_bad_linker_file_is_refused_in_one_line(self):
        status, err = self.run_tool("MEMORY { }\nSECTIONS { }\n")
        self.assertEqual(status, 2)
        self.assertEqual(err.count("\n"), 1)
        self.assertIn("no memory ranges", err)


if __name__ == "__main__":
    unittest.main()
