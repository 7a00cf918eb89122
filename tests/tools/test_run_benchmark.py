#!/usr/bin/env python3
"""tools/bench/run_benchmark.py's worst-step budget holds for every controller: a step of
MPTC-49 or MPTC-13, one that takes a new parameter set included, above 1.5 times the mean step
of the same configuration is a failure, as for DDC."""
import importlib.util
import os
import tempfile
import unittest

PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "bench",
                    "run_benchmark.py")
spec = importlib.util.spec_from_file_location("run_benchmark", PATH)
rb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rb)


def dumps(costs):
    """A combined callgrind file as `ctl-bench --worst-step` leaves it: one dump per step."""
    lines = ["version: 1", "creator: callgrind"]
    for config, rows in costs.items():
        for step, (cost, takes) in enumerate(rows):
            lines += ["", "desc: Trigger: Client Request: w-%s-%d-%d" % (config, step, takes),
                      "summary: %d" % cost]
    return "\n".join(lines) + "\n"


def steady(cost, n=10):
    return [(cost, 0)] * n


class WorstStepBudget(unittest.TestCase):
    def statistics(self, costs):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "callgrind.steps")
            with open(path, "w") as f:
                f.write(dumps(costs))
            return rb.step_statistics(rb.parse_step_dumps(path))

    def base(self):
        return {c: steady(2000 if c.startswith("ddc") else 10000) for c in rb.CONFIGS}

    def test_within_budget(self):
        costs = self.base()
        costs["mptc13_float"][4] = (14000, 1)  # 1.4x: a set taken, within 1.5x
        self.assertEqual(rb.budget_violations(self.statistics(costs), 1.5), [])

    def test_mptc_step_taking_a_new_set_over_budget_fails(self):
        costs = self.base()
        costs["mptc49_fixed"][3] = (25000, 1)
        bad = rb.budget_violations(self.statistics(costs), 1.5)
        self.assertTrue(bad)
        self.assertTrue(all(b.startswith("mptc49_fixed:") for b in bad), bad)
        self.assertIn("a step taking a new set costs 25000", " ".join(bad))

    def test_mptc13_ordinary_step_over_budget_fails(self):
        costs = self.base()
        costs["mptc13_fixed"][7] = (20000, 0)
        bad = rb.budget_violations(self.statistics(costs), 1.5)
        self.assertEqual(len(bad), 1)
        self.assertIn("mptc13_fixed: step 7 costs 20000", bad[0])

    def test_ddc_still_checked(self):
        costs = self.base()
        costs["ddc_float"][0] = (4000, 0)
        self.assertIn("ddc_float: step 0", rb.budget_violations(self.statistics(costs), 1.5)[0])


if __name__ == "__main__":
    unittest.main()
