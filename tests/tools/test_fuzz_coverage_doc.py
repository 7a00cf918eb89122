#!/usr/bin/env python3
"""tools/fuzz_coverage_doc.py: docs/faults.md's fuzz coverage block is written from llvm-cov's
export, and the CI check fails when the document differs or a listed unit is below 70 %."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import fuzz_coverage_doc  # noqa: E402

TOOL = fuzz_coverage_doc.__file__


def export(root, covered):
    """An llvm-cov export where every listed file and function has `covered` of 10 branches."""
    files, functions = [], []
    for _, path, func, _ in fuzz_coverage_doc.UNITS:
        full = os.path.join(root, path)
        if func:
            branches = [[k, 1, k, 9, 1 if 2 * k < covered else 0, 1 if 2 * k + 1 < covered else 0,
                         0, 0, 4] for k in range(5)]
            functions.append({"name": "x.c:" + func, "filenames": [full], "branches": branches})
        else:
            files.append({"filename": full, "summary": {"branches": {"count": 10,
                                                                     "covered": covered}}})
    return {"data": [{"files": files, "functions": functions}]}


class FuzzCoverageDoc(unittest.TestCase):
    def run_tool(self, d, covered, *mode):
        cov = os.path.join(d, "cov.json")
        with open(cov, "w") as f:
            json.dump(export(d, covered), f)
        return subprocess.run([sys.executable, TOOL, *mode, "--root", d, cov],
                              capture_output=True, text=True)

    def test_write_then_check(self):
        with tempfile.TemporaryDirectory() as d:
            doc = os.path.join(d, "faults.md")
            with open(doc, "w") as f:
                f.write("text\n<!-- fuzz-coverage -->\nold\n<!-- /fuzz-coverage -->\nend\n")
            self.assertEqual(self.run_tool(d, 8, "--write-doc", doc).returncode, 0)
            with open(doc) as f:
                text = f.read()
            self.assertIn("| 8 / 10 | 80.0 | 70 % |", text)
            self.assertTrue(text.endswith("<!-- /fuzz-coverage -->\nend\n"))
            self.assertEqual(self.run_tool(d, 8, "--check-doc", doc).returncode, 0)
            r = self.run_tool(d, 9, "--check-doc", doc)  # the figures moved: the doc is stale
            self.assertEqual(r.returncode, 1)
            self.assertIn("differs", r.stderr)

    def test_below_floor_fails(self):
        with tempfile.TemporaryDirectory() as d:
            r = self.run_tool(d, 6)
            self.assertEqual(r.returncode, 1)
            self.assertIn("below 70 %", r.stderr)
            self.assertEqual(self.run_tool(d, 7).returncode, 0)


if __name__ == "__main__":
    unittest.main()
