#!/usr/bin/env python3
"""The open-phase envelope of docs/faults.md (issue 23): every phase opening in each drive state,
in both arithmetics, run through the simulator; the table between the envelope markers of
docs/faults.md, and a check against the limits.

  tools/open_phase_envelope.py --write   run, check the limits, rewrite the table
  tools/open_phase_envelope.py --check   run, check the limits, compare with the committed table

Limits (issue 23): found within 10 ms at 20 % of rated torque and more (motoring, braking,
acceleration, reversal), within 100 ms at light and no load, before any phase reaches the trip
level (no other fault; the largest phase current below 15 A), the drive riding through (RUN,
the open phase's leg isolated); a commissioning sequence ends failed with reason open_phase,
nothing applied. Exit status 1 when a row breaks its limit or (--check) the table differs.
"""
import concurrent.futures
import os
import sys

import sim_doc_table

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DOC = os.path.join(ROOT, "docs", "faults.md")
BEGIN = "<!-- open-phase-envelope: tools/open_phase_envelope.py --write -->"
END = "<!-- /open-phase-envelope -->"
TRIP_A = 15.0
PHASES = "ABCDEF"
ARITHS = ("fixed", "float")
# In the encoder step's spin (the current vector turning). During the alignment before it
# (the first 1.0 .. 1.7 s, a standing vector) an open phase is found only when the spin starts:
# docs/commissioning.md, section 1.
COMMISSION_OPEN_S = 2.0

# name, the point in words, sixphase-sim arguments (the phase and arithmetic added), limit ms
CASES = (
    ("motoring", "1500 r/min, 3.5 N m", ["--scenario", "fault-open-phase", "--ride-through",
                                          "--speed", "1500", "--load", "3.5"], 10.0),
    ("braking", "460 r/min, -6.8 N m (overhauling)",
     ["--scenario", "fault-open-phase", "--ride-through", "--speed", "460", "--load", "-6.8",
      "--duration", "0.6"], 10.0),
    ("light load", "460 r/min, 0.5 N m", ["--scenario", "fault-open-phase", "--ride-through",
                                           "--speed", "460", "--load", "0.5"], 100.0),
    ("no load", "1500 r/min, 0 N m", ["--scenario", "fault-open-phase", "--ride-through",
                                       "--speed", "1500", "--load", "0"], 100.0),
    ("no load", "100 r/min, 0 N m", ["--scenario", "fault-open-phase", "--ride-through",
                                      "--speed", "100", "--load", "0"], 100.0),
    ("acceleration", "0 -> 800 r/min at 7 N m, opens at 0.1 s (329 r/min)",
     ["--scenario", "accel", "--ride-through", "--fault-time", "0.1", "--duration", "0.5"], 10.0),
    ("reversal", "800 -> -800 r/min, opens at 0.15 s (462 r/min, braking at -6.8 N m)",
     ["--scenario", "reversal", "--ride-through", "--fault-time", "0.15", "--duration", "0.6"],
     10.0),
    ("commissioning", "the encoder step's spin, opens at %.1f s" % COMMISSION_OPEN_S,
     ["--scenario", "commission", "--fault-time", repr(COMMISSION_OPEN_S)], 100.0),
)


def run_one(sim, case, phase, arith):
    _, point, args, _ = case
    return point, phase, arith, sim_doc_table.run_json(
        sim, ["--controller", "ddc", "--arith", arith, "--open-phase", phase] + args)


def judge(case, phase, m):
    """The row's figures and whether it keeps its limit."""
    name, _, _, limit_ms = case
    if name == "commissioning":
        c = m["commission"]
        ms = 1e3 * (c["duration_s"] - COMMISSION_OPEN_S)
        outcome = "%s %s, applied 0x%x" % (c["state"], c["reason"], c["applied_mask"])
        ok = (c["state"] == "failed" and c["reason"] == "open_phase" and ms <= limit_ms and
              c["applied_mask"] == 0 and m["drive_fault"] == 0 and
              c["phase_current_peak_a"] < TRIP_A)
        return ms, c["phase_current_peak_a"], None, outcome, ok
    op = m["open_phase"]
    ms = op["isolation_ms"]
    leg = op["isolated_leg"]
    peak = op["peak_after_event_a"]
    dip = op["speed_dip_rpm"] if name not in ("acceleration", "reversal") else None
    if m["drive_fault"] != 0:
        outcome = "FAULT %s" % m["fault_name"]
    elif leg == PHASES.index(phase) and m["final_drive_state"] == 3:
        outcome = "rides through"
    else:
        outcome = "not found (state %d)" % m["final_drive_state"]
    ok = (outcome == "rides through" and ms is not None and ms <= limit_ms and
          peak is not None and peak < TRIP_A)
    return ms, peak, dip, outcome, ok


def fmt(v, spec):
    return "n/a" if v is None else spec % v


def table(sim, jobs):
    jobs_list = [(c, p, a) for c in CASES for a in ARITHS for p in PHASES]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = [pool.submit(run_one, sim, c, p, a) for c, p, a in jobs_list]
        for f in futures:
            point, phase, arith, m = f.result()
            results[(point, phase, arith)] = m
    lines = ["| state | point | arithmetic | open phase | found after ms (limit) | largest phase "
             "current A | speed dip r/min | outcome | within limits |",
             "|---|---|---|---|---|---|---|---|---|"]
    failures = []
    for case in CASES:
        for arith in ARITHS:
            for phase in PHASES:
                ms, peak, dip, outcome, ok = judge(case, phase, results[(case[1], phase, arith)])
                lines.append("| %s | %s | %s | %s | %s (%g) | %s | %s | %s | %s |" % (
                    case[0], case[1], arith, phase, fmt(ms, "%.1f"), case[3], fmt(peak, "%.2f"),
                    fmt(dip, "%.1f"), outcome, "yes" if ok else "**no**"))
                if not ok:
                    failures.append("%s %s %s: %s after %s ms" % (case[0], arith, phase, outcome,
                                                                  fmt(ms, "%.1f")))
    return "\n".join(lines) + "\n", failures


def main():
    a = sim_doc_table.parser(__doc__.splitlines()[0], "docs/faults.md").parse_args()
    if not sim_doc_table.usable("open_phase_envelope", a):
        return 1
    block, failures = table(a.sim, a.jobs)
    status = sim_doc_table.update_block("open_phase_envelope", DOC, BEGIN, END, block, a)
    for line in failures:
        print("open_phase_envelope: outside the limits: " + line, file=sys.stderr)
    if failures:
        status = 1
    print("open_phase_envelope: %d rows, %d outside the limits" %
          (len(block.splitlines()) - 2, len(failures)))
    return status


if __name__ == "__main__":
    sys.exit(main())
