#!/usr/bin/env python3
"""tools/include_graph.py: a planted include cycle (two headers, or a .c and a header each
including the other's module) and an include a folder's rule does not allow each fail; a tree
without them passes; a listed known cycle passes until it is gone, then its entry fails."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "include_graph.py")


def run(*args):
    return subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True,
                          check=False)


class IncludeGraph(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.root = self.dir.name
        self.write("lib/low.h", "#pragma once\n#include <stdio.h>\n")
        self.write("lib/low.c", '#include "low.h"\n#include "cmocka.h"\n')
        self.write("app/high.h", '#pragma once\n#include "lib/low.h"\n')
        self.write("app/high.c", '#include "high.h"\n#include "lib/low.h"\n')
        self.write("lib/README.md", "Low.\n\nMay include: nothing\n")
        self.write("app/README.md", "High.\n\nMay include: lib\n")

    def tearDown(self):
        self.dir.cleanup()

    def write(self, name, text):
        path = os.path.join(self.root, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)

    def check(self, *extra):
        return run("--root", self.root, "--include", ".", *extra, "lib", "app")

    def test_tree_without_cycle_passes(self):
        r = self.check("--require-rules", ".")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("0 problem(s)", r.stdout)

    def test_two_headers_including_each_other_fail(self):
        self.write("lib/a.h", '#pragma once\n#include "b.h"\n')
        self.write("lib/b.h", '#pragma once\n#include "a.h"\n')
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("include cycle: lib/a <-> lib/b", r.stderr)

    def test_c_and_header_of_two_modules_fail(self):
        # low.c includes high.h while high.h includes low.h: modules low and high
        self.write("lib/low.c", '#include "low.h"\n#include "app/high.h"\n')
        self.write("lib/README.md", "Low.\n\nMay include: app\n")
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("include cycle: app/high <-> lib/low", r.stderr)
        self.assertIn('lib/low.c: #include "app/high.h"', r.stderr)

    def test_source_in_src_is_its_header_module(self):
        # mod.c in src/ with include/mod.h; other.h includes mod.h, mod.c includes other.h
        self.write("m/include/mod.h", "#pragma once\n")
        self.write("m/include/other.h", '#pragma once\n#include "mod.h"\n')
        self.write("m/src/mod.c", '#include "mod.h"\n#include "other.h"\n')
        r = run("--root", self.root, "--include", "m/include", "m")
        self.assertEqual(r.returncode, 1)
        self.assertIn("include cycle: m/include/mod <-> m/include/other", r.stderr)

    def test_known_cycle_passes_and_a_stale_entry_fails(self):
        self.write("lib/a.h", '#pragma once\n#include "b.h"\n')
        self.write("lib/b.h", '#pragma once\n#include "a.h"\n')
        self.write("known.txt", "# not yet broken\nlib/b <-> lib/a\n")
        known = os.path.join(self.root, "known.txt")
        r = self.check("--known", known)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("known include cycle (not yet broken): lib/a <-> lib/b", r.stderr)
        self.write("lib/b.h", "#pragma once\n")
        r = self.check("--known", known)
        self.assertEqual(r.returncode, 1)
        self.assertIn("known cycle no longer there", r.stderr)

    def test_include_against_the_rule_fails(self):
        self.write("lib/low.c", '#include "low.h"\n#include "app/high.h"\n')
        r = self.check()
        self.assertEqual(r.returncode, 1)
        self.assertIn("rule broken: lib/low.c", r.stderr)
        self.assertIn("(lib may not include app)", r.stderr)

    def test_folder_without_rule_fails_when_rules_required(self):
        self.write("app/README.md", "High, no rule.\n")
        r = self.check("--require-rules", ".")
        self.assertEqual(r.returncode, 1)
        self.assertIn("no rule: app/README.md", r.stderr)


if __name__ == "__main__":
    unittest.main()
