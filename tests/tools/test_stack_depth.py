#!/usr/bin/env python3
"""tools/stack_depth.py follows indirect calls through the notes kept next to their tables,
and fails on an indirect call no note resolves and on a note no call needs."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "stack_depth.py")

SOURCE = """
static int small(int x) { return x; }
static int deep(int x) { return helper(x); }
%s
static const struct { int cmd; handler_t fn; } commands[] = {
    {1, small}, /* a comment naming nothing */
    {2, deep},
};
int dispatch(int cmd) { return commands[cmd].fn(cmd); }
"""
NOTE = "/* indirect-call: dispatch -> table commands */"


def ci_file(src):
    """gcc's -fcallgraph-info=su output for SOURCE: dispatch calls through the table."""
    node = 'node: { title: "%s" label: "%s\\n%s:1:1\\n%d bytes (static)" }\n'
    return ('graph: { title: "%s"\n' % src +
            node % (src + ":small", "small", src, 8) +
            node % (src + ":deep", "deep", src, 16) +
            node % ("helper", "helper", src, 400) +
            node % ("dispatch", "dispatch", src, 24) +
            'node: { title: "__indirect_call" label: "Indirect Call Placeholder" shape : ellipse }\n'
            'edge: { sourcename: "%s:deep" targetname: "helper" label: "%s:3:1" }\n' % (src, src) +
            'edge: { sourcename: "dispatch" targetname: "__indirect_call" label: "%s:9:1" }\n'
            % src + "}\n")


class StackDepthIndirect(unittest.TestCase):
    def run_tool(self, note, *extra_notes):
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "table.c")
            with open(src, "w") as f:
                f.write(SOURCE % "\n".join((note,) + extra_notes))
            ci = os.path.join(d, "table.ci")
            with open(ci, "w") as f:
                f.write(ci_file(src))
            return subprocess.run([sys.executable, TOOL, "dispatch", ci], stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True)

    def test_table_is_followed(self):
        r = self.run_tool(NOTE)
        self.assertEqual(r.returncode, 0, r.stderr)
        # dispatch (24) -> deep (16) -> helper (400), not dispatch alone (24)
        self.assertIn("worst-case stack from dispatch: 440 bytes", r.stdout)
        self.assertIn("dispatch (24) -> deep (16) -> helper (400)", r.stdout)
        self.assertIn("indirect calls of dispatch: deep, small", r.stdout)

    def test_unresolved_indirect_call_fails(self):
        r = self.run_tool("")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("unresolved indirect call in dispatch", r.stderr)

    def test_stale_note_fails(self):
        r = self.run_tool(NOTE, "/* indirect-call: nobody -> small */")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("stale note", r.stderr)

    def test_unknown_target_fails(self):
        r = self.run_tool("/* indirect-call: dispatch -> smal */")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("'smal' is not a function", r.stderr)

    def test_a_pointer_the_image_never_sets(self):
        r = self.run_tool("/* indirect-call: dispatch -> nothing (a host-only hook) */")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("worst-case stack from dispatch: 24 bytes", r.stdout)

    def test_external_target_is_reported_not_measured(self):
        r = self.run_tool("/* indirect-call: dispatch -> small, external rom_routine */")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("rom_routine", r.stdout.split("not measured:")[1])


if __name__ == "__main__":
    unittest.main()
