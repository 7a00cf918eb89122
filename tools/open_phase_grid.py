#!/usr/bin/env python3
"""The open-phase detection grid and the false-alarm sweep of docs/faults.md ("Two open-phase
checks"), each between its markers.

Grid: each phase opening at 0.25 s at 100, 460 and 1500 r/min, loads +-1.4 (20 % of rated),
+-3.5 and +-7 N m (motoring and braking), seeds 1 to 3, fixed and float: 648 simulator runs
(DDC, minimum-loss ride-through, every board non-ideality on), summarised per load.
False alarms: healthy runs (steady, load-step, accel, reversal at 100, 460 and 1500 r/min, loads
0, 0.5, 2, -3.5 and 7 N m, seeds 1 to 10, fixed and float) of the DDC and of MPTC-13, none of
which may fault, and every fault-<name> scenario, seeds 1 to 10, both arithmetics, each of which
must report its own fault with one record.

  tools/open_phase_grid.py --write   run and rewrite the summary
  tools/open_phase_grid.py --check   run and compare with the committed summary (exit 1 if stale)

The envelope's limits are checked at its own points (tools/open_phase_envelope.py); this grid
reports, it does not judge: a run isolated later than 10 ms is a number in the table, not a
failure.
"""
import concurrent.futures
import statistics
import subprocess
import sys

import sim_doc_table

DOC = "docs/faults.md"
BEGIN = "<!-- open-phase-grid: tools/open_phase_grid.py --write -->"
END = "<!-- /open-phase-grid -->"
SPEEDS = (100, 460, 1500)
LOADS = (1.4, 3.5, 7.0)
PHASES = "ABCDEF"
SEEDS = (1, 2, 3)
ARITHS = ("fixed", "float")
WITHIN_MS = 10.0
FA_BEGIN = "<!-- open-phase-false-alarms: tools/open_phase_grid.py --write -->"
FA_END = "<!-- /open-phase-false-alarms -->"
FA_SCENARIOS = ("steady", "load-step", "accel", "reversal")
FA_LOADS = (0, 0.5, 2, -3.5, 7)
FA_CONTROLLERS = ("ddc", "mptc13")
FA_SEEDS = range(1, 11)


def run_one(sim, speed, load, phase, seed, arith):
    m = sim_doc_table.run_json(sim, [
        "--controller", "ddc", "--arith", arith, "--scenario", "fault-open-phase",
        "--ride-through", "--speed", str(speed), "--load", "%g" % load, "--open-phase", phase,
        "--seed", str(seed)])
    op = m["open_phase"]
    isolated = op["isolated_leg"] == PHASES.index(phase)
    return {"speed": speed, "load": load, "ms": op["isolation_ms"] if isolated else None,
            "peak": op["peak_after_event_a"] or 0.0,
            "fault": m["fault_name"] if m["drive_fault"] != 0 else None}


def summary_row(size, runs):
    found = [r for r in runs if r["ms"] is not None]
    ms = [r["ms"] for r in found]
    worst = max(found, key=lambda r: r["ms"]) if found else None
    faults = {}
    for r in runs:
        if r["fault"]:
            key = "%s at %d r/min, %+g N m" % (r["fault"], r["speed"], r["load"])
            faults[key] = faults.get(key, 0) + 1
    return "| +-%g | %d | %d | %d | %s | %s | %.2f | %s |" % (
        size, len(runs), len(found), sum(1 for v in ms if v <= WITHIN_MS),
        "%.1f" % statistics.median(ms) if ms else "n/a",
        "%.1f (%d r/min, %+g N m)" % (worst["ms"], worst["speed"], worst["load"]) if worst
        else "n/a", max(r["peak"] for r in runs),
        "; ".join("%d x %s" % (n, k) for k, n in sorted(faults.items())) or "none")


def table(sim, jobs):
    grid = [(s, sign * size, p, seed, a) for s in SPEEDS for size in LOADS for sign in (1, -1)
            for p in PHASES for seed in SEEDS for a in ARITHS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        runs = list(pool.map(lambda g: run_one(sim, *g), grid))
    lines = ["| load N m | runs | leg isolated | within %g ms | median ms | worst ms (where) | "
             "largest phase current after the opening A | other faults |" % WITHIN_MS,
             "|---|---|---|---|---|---|---|---|"]
    for size in LOADS:
        lines.append(summary_row(size, [r for r in runs if abs(r["load"]) == size]))
    return "\n".join(lines) + "\n", len(runs)


def fault_scenarios(sim):
    """The fault-<name> scenarios the simulator lists in its help."""
    out = subprocess.run([sim, "help"], capture_output=True, text=True, check=False)
    names = [w.split()[0] for w in out.stdout.splitlines() if w.startswith("  fault-")]
    if not names:
        raise RuntimeError("%s help lists no fault scenario" % sim)
    return names


def false_alarms(sim, jobs):
    healthy = [["--controller", c, "--scenario", sc, "--speed", str(sp), "--load", "%g" % ld,
                "--seed", str(seed), "--arith", a]
               for c in FA_CONTROLLERS for sc in FA_SCENARIOS for sp in SPEEDS for ld in FA_LOADS
               for seed in FA_SEEDS for a in ARITHS]
    faulty = [["--controller", "ddc", "--scenario", sc, "--seed", str(seed), "--arith", a]
              for sc in fault_scenarios(sim) for seed in FA_SEEDS for a in ARITHS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        h = list(pool.map(lambda args: sim_doc_table.run_json(sim, args), healthy))
        f = list(pool.map(lambda args: sim_doc_table.run_json(sim, args), faulty))
    lines = ["| runs | what | kept | not kept |", "|---|---|---|---|"]
    for c in FA_CONTROLLERS:
        mine = [m for m in h if m["controller"] == c]
        bad = sorted(set("%s %s %s" % (m["scenario"], m["arith"], m["fault_name"])
                         for m in mine if m["drive_fault"] != 0))
        lines.append("| %d | %s healthy: no fault | %d | %s |" % (
            len(mine), c.upper().replace("MPTC", "MPTC-"), sum(m["drive_fault"] == 0 for m in mine),
            "; ".join(bad) or "none"))
    own = [m for m in f if m["fault_code"] == m["fault_expected"] and m["fault_records"] == 1]
    bad = sorted(set("%s %s" % (m["scenario"], m["arith"]) for m in f if m not in own))
    lines.append("| %d | %d fault scenarios: their own fault, one record | %d | %s |" % (
        len(f), len(f) // (len(FA_SEEDS) * len(ARITHS)), len(own), "; ".join(bad) or "none"))
    return "\n".join(lines) + "\n", len(h) + len(f)


def main():
    a = sim_doc_table.parser(__doc__.splitlines()[0], DOC).parse_args()
    if not sim_doc_table.usable("open_phase_grid", a):
        return 1
    block, n = table(a.sim, a.jobs)
    doc = sim_doc_table.ROOT + "/" + DOC
    status = sim_doc_table.update_block("open_phase_grid", doc, BEGIN, END, block, a)
    fa_block, fa_n = false_alarms(a.sim, a.jobs)
    status |= sim_doc_table.update_block("open_phase_grid", doc, FA_BEGIN, FA_END, fa_block, a)
    print("open_phase_grid: %d grid runs, %d false-alarm runs" % (n, fa_n))
    return status


if __name__ == "__main__":
    sys.exit(main())
