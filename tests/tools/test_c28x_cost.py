#!/usr/bin/env python3
"""tools/bench/c28x_cost.py: host instructions are classified and priced, a conditional branch
is split into taken and not-taken executions from callgrind's jump records, an instruction
without a class fails the pricing, and run_benchmark.py's validation fails only when TI's figure
lies above the model's upper end."""
import importlib.util
import os
import sys
import tempfile
import unittest

BENCH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "bench")
sys.path.insert(0, BENCH)
import c28x_cost as cm  # noqa: E402

spec = importlib.util.spec_from_file_location("run_benchmark",
                                              os.path.join(BENCH, "run_benchmark.py"))
rb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rb)

# A dump as callgrind writes it with --dump-instr=yes --collect-jumps=yes: a branch at 0x1004
# executed 10 times and taken 3 times, a call whose inclusive cost must not count as self cost.
DUMP = """version: 1
positions: instr line
events: Ir
summary: 31
ob=(1) /x/ctl-bench
fl=(1) ???
fn=(1) f
0x1000 0 10
+4 0 10
jcnd=3/10 +8 0
* 0
+2 0 7
+3 0 1
cfn=(2) g
calls=1 0x2000 0
* 0 500
+3 0 3
"""

DIS = {0x1000: ("cmpl", "%eax,%edx", "f"), 0x1004: ("jne", "100c <f+0xc>", "f"),
       0x1006: ("imulq", "%rdx,%rax", "f"), 0x1009: ("callq", "2000 <g>", "f"),
       0x100c: ("retq", "", "f")}


class CostModelTest(unittest.TestCase):
    def test_classes(self):
        self.assertEqual(cm.classify("imulq", "%rdx,%rax"), "mul64")
        self.assertEqual(cm.classify("movl", "0x8(%rdi),%eax"), "load")
        self.assertEqual(cm.classify("movl", "%eax,0x8(%rdi)"), "store")
        self.assertEqual(cm.classify("comiss", "%xmm1,%xmm0"), "f_cmp")
        self.assertEqual(cm.classify("mulss", "0x4(%rdi),%xmm0"), "f_arith_mem")
        self.assertEqual(cm.classify("jmpq", "*%rax"), "jmp_ind")
        self.assertEqual(cm.classify("sarq", "$0x18,%rax"), "shift64")
        self.assertIsNone(cm.classify("vfmadd231ss", "%xmm1,%xmm2,%xmm0"))

    def test_dump_and_branches(self):
        with tempfile.NamedTemporaryFile("w", suffix=".cg", delete=False) as f:
            f.write(DUMP)
        try:
            counts, taken, summary = cm.parse_dump(f.name, "ctl-bench")
        finally:
            os.remove(f.name)
        self.assertEqual(summary, 31)
        self.assertEqual(counts, {0x1000: 10, 0x1004: 10, 0x1006: 7, 0x1009: 1, 0x100c: 3})
        self.assertEqual(taken, {0x1004: 3})
        per = cm.price(counts, taken, DIS)
        self.assertEqual(per["jcc_taken"][0], 3)
        self.assertEqual(per["jcc_not"][0], 7)
        self.assertEqual(per["mul64"][1:], [7 * 4, 7 * 10])
        self.assertEqual(cm.totals(per)[0], 31)

    def _narrow(self, listing):
        """narrow_product of the last instruction of a listing [(mnemonic, operands)]."""
        dis = {0x100 + 4 * i: (m, o, "f") for i, (m, o) in enumerate(listing)}
        last = max(dis)
        return cm.narrow_product(last, dis, cm.Blocks(dis))

    def test_a_product_of_32_bit_values_is_priced_as_one(self):
        # sign extension, a 32-bit write, a 32-bit immediate, a copy and a frame slot
        self.assertTrue(self._narrow([("movslq", "0x4(%rdi),%rax"), ("movl", "(%rsi),%edx"),
                                      ("imulq", "%rdx,%rax")]))
        self.assertTrue(self._narrow([("movslq", "(%rdi),%rcx"), ("movq", "%rcx,%rax"),
                                      ("imulq", "$0x2aaaab,%rax,%rax")]))
        self.assertTrue(self._narrow([("movslq", "(%rdi),%rcx"), ("movq", "%rcx,0x8(%rsp)"),
                                      ("movl", "(%rsi),%edx"), ("imulq", "0x8(%rsp),%rdx")]))
        self.assertTrue(self._narrow([("movslq", "(%rdi),%rcx"), ("imulq", "%rcx,%rcx"),
                                      ("sarq", "$0x20,%rcx"), ("movslq", "(%rsi),%rax"),
                                      ("imulq", "%rcx,%rax")]))
        dis = {0x100: ("movslq", "(%rdi),%rax", "f"), 0x104: ("imulq", "%rax,%rax", "f")}
        per = cm.price({0x104: 2}, {}, dis)
        self.assertEqual(per["mul32x32"][1:], [2 * 4, 2 * 5])
        self.assertEqual(per["mul64"][0], 0)

    def test_a_product_not_shown_32_bit_keeps_the_wide_price(self):
        # a 64-bit sum, a right shift by less than 32, a 64-bit load, a caller-saved register
        # across a call, a path where the operand is wide
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("addq", "%rsi,%rax"),
                                       ("movslq", "(%rsi),%rdx"), ("imulq", "%rdx,%rax")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("sarq", "$0x18,%rax"),
                                       ("movslq", "(%rsi),%rdx"), ("imulq", "%rdx,%rax")]))
        self.assertFalse(self._narrow([("movq", "(%rdi),%rax"), ("movslq", "(%rsi),%rdx"),
                                       ("imulq", "%rdx,%rax")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("movslq", "(%rsi),%rbx"),
                                       ("callq", "200 <g>"), ("imulq", "%rbx,%rax")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("je", "10c <f+0xc>"),
                                       ("movq", "(%rsi),%rax"), ("movslq", "(%rsi),%rdx"),
                                       ("imulq", "%rdx,%rax")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("imulq", "(%rsi),%rax")]))

    def test_what_may_change_a_value_unseen_makes_it_wide(self):
        # the upper half of a tracked slot written; the frame's address taken (a store through
        # it could write the slot); an exchange; an indirect jump anywhere in the function
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rcx"), ("movq", "%rcx,0x8(%rsp)"),
                                       ("movl", "%esi,0xc(%rsp)"), ("movl", "(%rsi),%edx"),
                                       ("imulq", "0x8(%rsp),%rdx")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rcx"), ("movq", "%rcx,0x8(%rsp)"),
                                       ("leaq", "0x8(%rsp),%rdi"), ("movl", "(%rsi),%edx"),
                                       ("imulq", "0x8(%rsp),%rdx")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("movslq", "(%rsi),%rdx"),
                                       ("xchgq", "%rax,%r8"), ("imulq", "%rdx,%rax")]))
        self.assertFalse(self._narrow([("movslq", "(%rdi),%rax"), ("movslq", "(%rsi),%rdx"),
                                       ("imulq", "%rdx,%rax"), ("jmpq", "*%rcx")]))
        # a sign extension is not a string move (movslq starts as movs does)
        self.assertTrue(self._narrow([("movslq", "(%rdi),%rax"), ("movslq", "(%rsi),%rdx"),
                                      ("imulq", "%rdx,%rax")]))

    def test_a_callee_saved_register_stays_narrow_across_a_call(self):
        self.assertTrue(self._narrow([("movslq", "(%rdi),%rbx"), ("callq", "200 <g>"),
                                      ("movslq", "(%rsi),%rax"), ("imulq", "%rbx,%rax")]))

    def test_unknown_instruction_fails(self):
        with self.assertRaises(ValueError):
            cm.price({0x1000: 1}, {}, {0x1000: ("vfmadd231ss", "%xmm1,%xmm2,%xmm0", "f")})

    def test_validation_fails_only_above_the_upper_end(self):
        row = ("r", 63, "TI", "src", 10, 50.0, 96.0, 238.0)
        self.assertEqual(rb.validation_violations([row]), [])
        self.assertEqual(len(rb.validation_violations([row[:1] + (300,) + row[2:]])), 1)

    def test_every_price_is_an_interval_with_a_source(self):
        for desc, lo, hi, src, note in cm.PRICES.values():
            self.assertLessEqual(lo, hi, desc)
            self.assertIn(src, cm.SOURCES, desc)


if __name__ == "__main__":
    unittest.main()
