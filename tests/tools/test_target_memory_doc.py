#!/usr/bin/env python3
"""tools/target_memory_doc.py: docs/porting.md's stack and RAM figures are written from the
tools' summaries, and the CI check fails as soon as the document and the tools disagree."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "target_memory_doc.py")


def write_build(d, code_words, isr_words, from_flash):
    os.makedirs(d)
    with open(os.path.join(d, "stack_bound.json"), "w") as f:
        build = {"build": "noinline", "background_words": 600, "isr_words": isr_words,
                 "context_words": 56, "bound_words": 656 + isr_words,
                 "background_path": ["main (20, m0)", "fw_startup (150, x86)"],
                 "isr_path": ["fw_adc_isr (28, x86)", "ctl_step (32, x86)"]}
        json.dump({"bound_words": 656 + isr_words, "stack_words": 1792,
                   "free_percent": round(100.0 - 100.0 * (656 + isr_words) / 1792, 1),
                   "worst_build": "noinline", "builds": [dict(build, build="o2"), build]}, f)
    with open(os.path.join(d, "ram.json"), "w") as f:
        json.dump({"ranges": {"RAML0L3": {"length": 16384, "use": code_words, "ram": True},
                              "RAML4L5": {"length": 8192, "use": 4502, "ram": True},
                              "RAML6L7": {"length": 8192, "use": 6901, "ram": True}},
                   "outputs": {"ramfuncs": {"words": code_words, "load": ["FLASHD"],
                                            "run": ["RAML0L3"]},
                               "ramconsts": {"words": 4502, "load": ["FLASHA"],
                                             "run": ["RAML4L5"]},
                               ".ebss": {"words": 6901, "load": ["RAML6L7"],
                                         "run": ["RAML6L7"]},
                               ".text": {"words": 28000, "load": ["FLASHC", "FLASHB"],
                                         "run": ["FLASHC", "FLASHB"]}},
                   "rts_in_ram": ["l_div28.asm.obj"], "boot_path": ["_c_int00", "main"],
                   "from_flash": from_flash, "code_factor": [1.0, 1.5], "data_factor": 1.5,
                   "ram_limit": 0.9}, f)


class TargetMemoryDoc(unittest.TestCase):
    def test_write_then_check_then_drift(self):
        with tempfile.TemporaryDirectory() as d:
            doc = os.path.join(d, "porting.md")
            with open(doc, "w") as f:
                f.write("before\n<!-- target-memory -->\nold 14998 words\n"
                        "<!-- /target-memory -->\nafter\n")
            write_build(os.path.join(d, "float"), 10237, 676, [])
            write_build(os.path.join(d, "fixed"), 13663, 744, ["ctl_mptc_select"])
            base = [sys.executable, TOOL, doc, "--stack-words", "1792", "--float",
                    os.path.join(d, "float"), "--fixed", os.path.join(d, "fixed")]

            def run(mode):
                return subprocess.run(base[:2] + [mode] + base[2:], stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE, text=True)

            self.assertNotEqual(run("--check-doc").returncode, 0)  # the hand-written block
            self.assertEqual(run("--write-doc").returncode, 0)
            text = open(doc).read()
            self.assertTrue(text.startswith("before\n") and text.endswith("after\n"))
            self.assertIn("| float (default) | 10237 words (62 %) of RAML0L3 | 4502 words (55 %) "
                          "of RAML4L5 | 6901 words (84 %) of RAML6L7 | `l_div28.asm.obj` |", text)
            self.assertIn("| fixed (Q24; `ctl_mptc_select` in flash) | 13663 words (83 %) of "
                          "RAML0L3 |", text)
            self.assertIn("Boot path before the RAM copy (runs where it is loaded): `_c_int00`, "
                          "`main`.", text)
            self.assertIn("| 600 + 676 + 56 = 1332 words (26 % left; -fno-inline) |", text)
            self.assertIn("All code of the float image: `.text` 28000 + `ramfuncs` 10237 = 38237 "
                          "words, against 34816 words of SARAM", text)
            self.assertIn("| 600 + 744 + 56 = 1400 words (22 % left; -fno-inline) |", text)
            self.assertIn("Deepest paths (float, -fno-inline): background `main -> fw_startup`; "
                          "control interrupt `fw_adc_isr -> ctl_step`.", text)
            self.assertNotIn("14998", text)
            r = run("--check-doc")
            self.assertEqual(r.returncode, 0, r.stderr)
            write_build(os.path.join(d, "float2"), 10300, 676, [])  # the code grew
            base[base.index(os.path.join(d, "float"))] = os.path.join(d, "float2")
            r = run("--check-doc")
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("out of date", r.stderr)

    def test_missing_markers_fail(self):
        with tempfile.TemporaryDirectory() as d:
            doc = os.path.join(d, "porting.md")
            with open(doc, "w") as f:
                f.write("no block\n")
            write_build(os.path.join(d, "b"), 1, 1, [])
            r = subprocess.run([sys.executable, TOOL, "--write-doc", doc, "--stack-words", "1",
                                "--float", os.path.join(d, "b"), "--fixed", os.path.join(d, "b")],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("no <!-- target-memory -->", r.stderr)


if __name__ == "__main__":
    unittest.main()
