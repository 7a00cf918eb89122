#!/usr/bin/env python3
"""tools/doc_claims.py: a number copied into a doc is checked against its source; a planted
stale number, a source that changed and a source that no longer says it each fail, and the
repository's own registry holds."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")
TOOL = os.path.join(TOOLS, "doc_claims.py")


def run(*args):
    return subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True,
                          check=False)


class DocClaims(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.root = self.dir.name
        self.write("gen.md", "| DDC | fixed | 1864 | 0.239 |\n")
        self.write("prose.md", "The ratio is 0.239 in fixed point.\n")
        self.registry = os.path.join(self.root, "claims.txt")
        self.write("claims.txt", "# a claim\nprose.md || ratio is {} in fixed || gen.md || "
                   r"^\| DDC \| fixed \| [0-9]+ \| ([0-9.]+) \|" + "\n")

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, text):
        with open(os.path.join(self.root, name), "w", encoding="utf-8") as f:
            f.write(text)

    def check(self):
        return run("--registry", self.registry, "--root", self.root)

    def test_current_claim_holds(self):
        r = self.check()
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_planted_stale_number_fails(self):
        self.write("prose.md", "The ratio is 0.182 in fixed point.\n")
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("should say 'ratio is 0.239 in fixed'", r.stderr)
        self.assertIn("(it says 'ratio is 0.182 in fixed')", r.stderr)

    def test_changed_source_fails(self):
        self.write("gen.md", "| DDC | fixed | 1800 | 0.231 |\n")
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("0.231", r.stderr)

    def test_source_that_no_longer_says_it_fails(self):
        self.write("gen.md", "nothing here\n")
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("no longer matches", r.stderr)

    def test_malformed_registry_refused(self):
        self.write("claims.txt", "prose.md || no placeholder || gen.md || (x)\n")
        r = self.check()
        self.assertEqual(r.returncode, 2)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1)

    def test_repository_registry_holds(self):
        r = run()
        self.assertEqual(r.returncode, 0, r.stderr)


if __name__ == "__main__":
    unittest.main()
