#!/usr/bin/env python3
"""Every controller of the product side by side (issue 27), run through the simulator and
written between the comparison's markers of docs/results.md:

  (a) at the sampling rate the F28335 can execute for each controller and arithmetic by the cost
      model (docs/performance.md: the worst step's upper end within RATE_BUDGET of the period,
      at most the paper's 10 kHz);
  (b) at equal average switching frequency: each controller's sampling rate set (bisection) so
      that it switches as often as the product DDC at 10 kHz, the rate's feasibility stated.

Steady state at rated load (THD, THD_50, torque ripple, x-y rms, switching frequency, inverter
loss estimate), load step (the speed's settling and dip) and reversal (settling and overshoot),
seeds 1..5, means with 95 % intervals (Student t, 4 degrees of freedom), host instructions and
the F28335 estimate per step (docs/performance.md), and a summary of which controller wins
which metric, by how much and whether the margin exceeds the seed scatter (the intervals of
the two best do not overlap).

Each controller runs on the board's +-20 A sensors unless they clip for it; then on the
smallest wider span that does not (the row says which). With the protection on; a controller
that trips is run again with it off and the row says so.

  tools/controller_comparison.py --write   run and rewrite the tables
  tools/controller_comparison.py --check   run and compare with the committed tables
"""
import concurrent.futures
import math
import os
import re
import statistics
import subprocess
import sys

import sim_doc_table

DOC = os.path.join(sim_doc_table.ROOT, "docs", "results.md")
PERF = os.path.join(sim_doc_table.ROOT, "docs", "performance.md")
BEGIN = "<!-- controller-comparison: tools/controller_comparison.py --write -->"
END = "<!-- /controller-comparison -->"
SEEDS = (1, 2, 3, 4, 5)
T_95_4DOF = 2.776  # Student t, 97.5 % quantile, 4 degrees of freedom
ARITHS = ("fixed", "float")
PAPER_FS = 10000.0
RATE_BUDGET = 0.6  # share of the period the control step may take (protection, ISR, background)
RATE_STEP = 100.0
SPANS = (40.0, 60.0, 80.0, 100.0, 200.0)  # full sensor span, A; 40 = the board's +-20 A
SWITCH_MATCH = 0.02  # equal switching: within 2 % of the product DDC's
# (key, label, sixphase-sim arguments, the cost model's row name in docs/performance.md)
KNOWN = {
    "ddc": ("DDC, product", [], "DDC"),
    "mptc49": ("MPTC-49", [], "MPTC-49"),
    "mptc13": ("MPTC-13", [], "MPTC-13"),
    "foc": ("FOC-VSD", [], "FOC-VSD"),
    "vvmptc": ("VV-MPTC", [], "VV-MPTC"),
}
PAPER = ("ddc-paper", "DDC, paper", ["--paper-ddc"], "DDC")
# (metric key in the run's JSON, label, format, scenario)
STEADY = (("thd_percent", "THD %", "%.1f"), ("thd_h50_percent", "THD_50 %", "%.1f"),
          ("torque_ripple_nm", "ripple N m", "%.3f"), ("xy_current_rms_a", "x-y rms A", "%.2f"),
          ("switching_freq_hz", "f_sw Hz", "%.0f"), ("inverter_loss_w", "inverter loss W",
                                                     "%.1f"))
STEP = (("speed_settle_ms", "load step: settling ms", "%.1f"),
        ("speed_peak_error_rpm", "load step: dip r/min", "%.1f"))
REVERSAL = (("speed_settle_ms", "reversal: settling ms", "%.1f"),
            ("speed_peak_error_rpm", "reversal: overshoot r/min", "%.1f"))


def fail(msg):
    print("controller_comparison: " + msg, file=sys.stderr)
    sys.exit(1)


def controllers(sim):
    """The controllers sixphase-sim offers (its --controller choices), the paper's DDC first."""
    out = subprocess.run([sim, "help"], capture_output=True, text=True, check=False).stdout
    m = re.search(r"--controller \{([a-z0-9,]+)\}", out)
    if not m:
        fail("%s help lists no --controller choices" % sim)
    rows = [PAPER]
    for key in m.group(1).split(","):
        if key not in KNOWN:
            fail("controller '%s' has no label here (KNOWN)" % key)
        rows.append((key,) + KNOWN[key])
    return rows


def cost_rows():
    """{(cost-model name, arith): (host instructions, us low, us high, worst us high)}."""
    rows = {}
    pat = re.compile(r"^\| ([A-Za-z0-9-]+) \| (fixed|float) \| ([0-9]+) \| ([0-9]+) \| [0-9]+ - "
                     r"[0-9]+ \| ([0-9.]+) - ([0-9.]+) \| [0-9.]+ - ([0-9.]+) \|", re.M)
    with open(PERF, encoding="utf-8") as f:
        for m in pat.finditer(f.read()):
            rows[(m.group(1), m.group(2))] = (int(m.group(3)), float(m.group(5)),
                                              float(m.group(6)), float(m.group(7)))
    return rows


def feasible_rate(worst_us_high):
    fs = min(PAPER_FS, RATE_BUDGET * 1e6 / worst_us_high)
    return math.floor(fs / RATE_STEP) * RATE_STEP


def interval(values):
    mean = statistics.fmean(values)
    half = T_95_4DOF * statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else 0
    return mean, half


class Runs:
    """The simulator runs, a batch at a time on --jobs workers."""

    def __init__(self, sim, jobs):
        self.sim = sim
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)

    def batch(self, arg_lists):
        return list(self.pool.map(lambda a: sim_doc_table.run_json(self.sim, a), arg_lists))

    def seeds(self, args):
        return self.batch([args + ["--seed", str(s)] for s in SEEDS])


def args_of(row, arith, fs, scenario, span, protect):
    a = ["--controller", row[0].replace("-paper", ""), "--arith", arith, "--fs", "%g" % fs,
         "--scenario", scenario, "--sensor-span", "%g" % span] + row[2]
    return a if protect else a + ["--no-protect"]


def setup_for(runs, row, arith, fs):
    """(span, protect, note, steady runs): the protection on unless it trips, then off; the
    board's sensors unless they clip in the runs kept, then the smallest wider span that does
    not."""
    for span in SPANS:
        steady = runs.seeds(args_of(row, arith, fs, "steady", span, True))
        faults = sorted(set(m["fault_name"] for m in steady if m["drive_fault"] != 0))
        if faults:
            steady = runs.seeds(args_of(row, arith, fs, "steady", span, False))
        if any(m["adc_clipped_samples"] > 0 for m in steady) and span != SPANS[-1]:
            continue
        note = "+-%g A" % (span / 2)
        if faults:
            return span, False, note + ", trips (%s): protection off" % "/".join(faults), steady
        return span, True, note, steady
    raise AssertionError("unreachable")


def cell(values, fmt):
    if any(v is None for v in values):
        return "n/a (%d of %d)" % (sum(v is None for v in values), len(values))
    mean, half = interval(values)
    return (fmt + " +- " + fmt) % (mean, half)


def measure(runs, row, arith, fs):
    span, protect, note, steady = setup_for(runs, row, arith, fs)
    step = runs.seeds(args_of(row, arith, fs, "load-step", span, protect))
    rev = runs.seeds(args_of(row, arith, fs, "reversal", span, protect))
    values = {}
    for group, metrics in ((steady, STEADY), (step, STEP), (rev, REVERSAL)):
        for key, label, fmt in metrics:
            values[label] = ([m[key] for m in group], fmt)
    return span, protect, note, values


def equal_switching_rate(runs, row, arith, target, span, protect):
    """The sampling rate at which the controller switches as often as target (seed 1)."""
    lo, hi = 1000.0, 40000.0
    fs = PAPER_FS
    for _ in range(12):
        m = runs.batch([args_of(row, arith, fs, "steady", span, protect) + ["--seed", "1"]])[0]
        f = m["switching_freq_hz"]
        if abs(f - target) <= SWITCH_MATCH * target:
            break
        lo, hi = (fs, hi) if f < target else (lo, fs)
        fs = round(math.sqrt(lo * hi) / RATE_STEP) * RATE_STEP
    return fs


def table_a(results, arith, cost):
    labels = [l for _, l, _ in STEADY + STEP + REVERSAL]
    lines = ["Arithmetic: %s. Mean +- 95 %% interval over seeds 1..5." % arith, "",
             "| controller | rate kHz | sensors | " + " | ".join(labels) +
             " | host instructions / step | F28335 us / step |",
             "|---" * (len(labels) + 5) + "|"]
    for row, fs, note, values in results:
        c = cost[(row[3], arith)]
        lines.append("| %s | %.1f | %s | %s | %d | %.1f - %.1f |" % (
            row[1], fs / 1e3, note, " | ".join(cell(*values[l]) for l in labels), c[0], c[1],
            c[2]))
    return lines


def summary(results, arith):
    lines = ["| metric (%s, F28335 rates) | best | runner-up | margin | beyond the seed scatter |"
             % arith, "|---|---|---|---|---|"]
    wins = {}
    for _, label, fmt in STEADY + STEP + REVERSAL:
        if label == "f_sw Hz":
            continue
        scored = []
        for row, _, _, values in results:
            vals, _ = values[label]
            if all(v is not None for v in vals):
                scored.append((interval(vals), row[1]))
        scored.sort()
        if len(scored) < 2:
            continue
        (m1, h1), n1 = scored[0]
        (m2, h2), n2 = scored[1]
        apart = m1 + h1 < m2 - h2
        lines.append("| %s | %s (%s) | %s (%s) | %s (%.0f %%) | %s |" % (
            label, n1, fmt % m1, n2, fmt % m2, fmt % (m2 - m1),
            100.0 * (m2 - m1) / m2 if m2 else 0.0, "yes" if apart else "no"))
        if apart:
            wins.setdefault(n1, []).append(label)
    lines += ["", "Best beyond the seed scatter (%s): %s." % (arith, "; ".join(
        "%s: %s" % (name, ", ".join(labels)) for name, labels in sorted(wins.items())) or "none")]
    return lines


def table_b(runs, rows, arith, cost, setups):
    """Equal switching: every controller at the rate where it switches as the product DDC."""
    product = [r for r in rows if r[0] == "ddc"][0]
    span, protect = setups[(product[0], arith)]
    target = statistics.fmean(m["switching_freq_hz"] for m in runs.seeds(
        args_of(product, arith, PAPER_FS, "steady", span, protect)))
    labels = [l for _, l, _ in STEADY]
    lines = ["Arithmetic: %s; the product DDC switches %.0f Hz at 10 kHz." % (arith, target), "",
             "| controller | rate kHz | F28335 can run it | sensors | " + " | ".join(labels) + " |",
             "|---" * (len(labels) + 4) + "|"]
    for row in rows:
        span, protect = setups[(row[0], arith)]
        fs = PAPER_FS if row[0] == "ddc" else equal_switching_rate(runs, row, arith, target,
                                                                  span, protect)
        _, _, note, steady = setup_for(runs, row, arith, fs)
        can = fs <= feasible_rate(cost[(row[3], arith)][3])
        lines.append("| %s | %.1f | %s | %s | %s |" % (
            row[1], fs / 1e3, "yes" if can else "no (at most %.1f kHz)" %
            (feasible_rate(cost[(row[3], arith)][3]) / 1e3), note,
            " | ".join(cell([m[k] for m in steady], f) for k, _, f in STEADY)))
    return lines


def build(sim, jobs):
    runs = Runs(sim, jobs)
    rows = controllers(sim)
    cost = cost_rows()
    out, setups = [], {}
    for row in rows:
        for arith in ARITHS:
            if (row[3], arith) not in cost:
                fail("docs/performance.md has no F28335 estimate for %s %s (run the benchmark)"
                     % (row[3], arith))
    for arith in ARITHS:
        results = []
        for row in rows:
            fs = feasible_rate(cost[(row[3], arith)][3])
            span, protect, note, values = measure(runs, row, arith, fs)
            setups[(row[0], arith)] = (span, protect)
            results.append((row, fs, note, values))
        out += ["#### At the rates the F28335 can execute (%s)" % arith, ""]
        out += table_a(results, arith, cost) + [""] + summary(results, arith) + [""]
    for arith in ARITHS:
        out += ["#### At equal switching frequency (%s)" % arith, ""]
        out += table_b(runs, rows, arith, cost, setups) + [""]
    return "\n".join(out)


def main():
    a = sim_doc_table.parser(__doc__.splitlines()[0], "docs/results.md").parse_args()
    if not sim_doc_table.usable("controller_comparison", a):
        return 1
    block = build(a.sim, a.jobs)
    return sim_doc_table.update_block("controller_comparison", DOC, BEGIN, END, block, a)


if __name__ == "__main__":
    sys.exit(main())
