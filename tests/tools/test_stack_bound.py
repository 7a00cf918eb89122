#!/usr/bin/env python3
"""tools/stack_bound.py: each function counts at its largest frame over the proxies, the
bound refuses recursion, an unresolved indirect call and an unknown routine, and the check
fails when the bound leaves less than the required share of the stack."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "stack_bound.py")
CALL = 16  # stack_bound.CALL_WORDS: return address and save-on-entry registers per function
CONTEXT = 56  # the interrupt context of stack_bound.CONTEXT

SOURCE = """
static int leaf(int x) { return x; }
static int deep(int x) { return leaf(x); }
%s
static const handler_t table[] = {leaf, deep};
int main(void) { return table[0](0); }
void isr(void) { (void)deep(1); }
"""
NOTE = "/* indirect-call: main -> table table */"


def node(src, name, nbytes):
    return 'node: { title: "%s" label: "%s\\n%s:1:1\\n%d bytes (static)" }\n' % (
        name, name.split(":")[-1], src, nbytes)


def edge(src, caller, callee):
    return 'edge: { sourcename: "%s" targetname: "%s" label: "%s:2:1" }\n' % (
        caller, callee, src)


class StackBound(unittest.TestCase):
    def build(self, d, m0, avr, x86, note=NOTE, extra_edges=()):
        """One build directory: main -> (table) -> deep -> leaf; isr -> deep. Frames in bytes
        per proxy as {name: bytes}."""
        src = os.path.join(d, "prog.c")
        with open(src, "w") as f:
            f.write(SOURCE % note)
        b = os.path.join(d, "o2")
        for proxy in ("m0", "avr", "x86"):
            os.makedirs(os.path.join(b, proxy))
        text = 'graph: { title: "%s"\n' % src
        for name in ("main", "isr", "deep", "leaf"):
            text += node(src, (src + ":" + name) if name in ("deep", "leaf") else name,
                         m0[name])
        text += ('node: { title: "__indirect_call" label: "Indirect Call Placeholder" '
                 'shape : ellipse }\n')
        text += edge(src, "main", "__indirect_call") + edge(src, "isr", src + ":deep")
        text += edge(src, src + ":deep", src + ":leaf")
        for caller, callee in extra_edges:
            text += edge(src, caller, callee)
        with open(os.path.join(b, "m0", "prog.ci"), "w") as f:
            f.write(text + "}\n")
        for proxy, frames in (("avr", avr), ("x86", x86)):
            with open(os.path.join(b, proxy, "prog.su"), "w") as f:
                for name, nbytes in sorted(frames.items()):
                    f.write("prog.c:1:1:%s\t%d\tstatic\n" % (name, nbytes))
        return b

    def run_tool(self, build, stack_words=1000, *extra):
        summary = os.path.join(os.path.dirname(build), "bound.json")
        r = subprocess.run([sys.executable, TOOL, "--background", "main", "--isr", "isr",
                            "--stack-words", str(stack_words), "--summary", summary] +
                           list(extra) + [build], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        if not os.path.exists(summary):
            return r, None
        with open(summary) as f:
            return r, json.load(f)

    def frames(self):
        m0 = {"main": 8, "isr": 8, "deep": 16, "leaf": 4}
        return m0, dict(m0), dict(m0)

    def test_largest_frame_over_the_proxies(self):
        with tempfile.TemporaryDirectory() as d:
            m0, avr, x86 = self.frames()
            avr["deep"] = 40   # larger on the AVR than on the M0 and the i386
            x86["main"] = 30   # larger on the i386
            r, s = self.run_tool(self.build(d, m0, avr, x86))
            self.assertEqual(r.returncode, 0, r.stderr)
            build = s["builds"][0]
            # main: i386 30 B -> 16 words; deep: AVR 40 B -> 20; leaf 4 B -> 2; each + CALL
            self.assertEqual(build["background_words"], (16 + CALL) + (20 + CALL) + (2 + CALL))
            self.assertEqual(build["isr_words"], (4 + CALL) + (20 + CALL) + (2 + CALL))
            self.assertEqual(s["bound_words"],
                             build["background_words"] + build["isr_words"] + CONTEXT)
            self.assertIn("deep (%d, avr)" % (20 + CALL), build["background_path"])
            self.assertIn("main (%d, x86)" % (16 + CALL), build["background_path"])

    def test_odd_words_round_up_to_even(self):
        with tempfile.TemporaryDirectory() as d:
            m0, avr, x86 = self.frames()
            m0["leaf"] = 6  # 3 words -> 4: 32-bit data at even addresses
            r, s = self.run_tool(self.build(d, m0, avr, x86))
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("leaf (%d, m0)" % (4 + CALL), s["builds"][0]["isr_path"])

    def test_recursion_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "prog.c")
            b = self.build(d, *self.frames(), extra_edges=[(src + ":leaf", src + ":deep")])
            r, _ = self.run_tool(b)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("recursion through", r.stderr)

    def test_unresolved_indirect_call_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            r, _ = self.run_tool(self.build(d, *self.frames(), note=""))
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("unresolved indirect call in main", r.stderr)

    def test_unknown_routine_is_refused_library_and_fpu_ones_are_not(self):
        with tempfile.TemporaryDirectory() as d:
            b = self.build(d, *self.frames(), extra_edges=[("isr", "mystery")])
            r, _ = self.run_tool(b)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("mystery is called but neither compiled here", r.stderr)
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "prog.c")
            b = self.build(d, *self.frames(), extra_edges=[(src + ":leaf", "__aeabi_ldivmod"),
                                                           (src + ":leaf", "__aeabi_fadd")])
            r, s = self.run_tool(b)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(s["builds"][0]["isr_path"][-1],
                             "__aeabi_ldivmod (%d, run-time library allowance)" % s["rts_words"])

    def test_less_than_a_fifth_left_fails(self):
        with tempfile.TemporaryDirectory() as d:
            b = self.build(d, *self.frames())
            r, s = self.run_tool(b)
            need = s["bound_words"]
            fits = int(need / 0.8) + 1  # leaves just over 20 %
            r, s = self.run_tool(b, fits)
            self.assertEqual(r.returncode, 0, r.stderr)
            r, s = self.run_tool(b, need + 1)  # fits, but leaves less than 20 %
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("leaves less than 20 %", r.stderr)
            self.assertLess(s["free_percent"], 20.0)

    def test_bad_arguments(self):
        with tempfile.TemporaryDirectory() as d:
            r, _ = self.run_tool(os.path.join(d, "missing"))
            self.assertNotEqual(r.returncode, 0)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1)
            r, _ = self.run_tool(self.build(d, *self.frames()), 0)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("--stack-words must be positive", r.stderr)
            r = subprocess.run([sys.executable, TOOL, "--isr", "isr", d], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
            self.assertNotEqual(r.returncode, 0)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn("stack_bound: the following arguments are required", r.stderr)


if __name__ == "__main__":
    unittest.main()
