#!/usr/bin/env python3
"""Commissioning accuracy over the range of machines (issue 25): the drive's identification run
in the simulator on machines at the corners of the range, both arithmetics, every board
non-ideality on; the table between the markers of docs/commissioning.md, and a check of every
result against its limit and its own uncertainty.

  tools/commission_grid.py --write   run, check, rewrite the table
  tools/commission_grid.py --check   run, check, compare with the committed table

A result passes when the sequence ends done, the quantity's quality is ok, its error is within
the limit (R 2 %, L_d and L_q 3 %, L_xy 5 %, psi_f 2 %, encoder offset 1 deg, inertia 5 %,
friction 20 % or 2e-4 N m s) and within 3 times the sigma the drive reports. The results known
to fail are listed in tools/commission_grid_known.txt (open work of issue 25; --write
--write-known records today's): exit status 1 when a result fails that is not listed, when a
listed one passes (take it off the list), or (--check) when the table differs.
"""
import concurrent.futures
import os
import sys

import sim_doc_table

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DOC = os.path.join(ROOT, "docs", "commissioning.md")
BEGIN = "<!-- commission-grid: tools/commission_grid.py --write -->"
END = "<!-- /commission-grid -->"
ARITHS = ("fixed", "float")
SIGMAS = 3.0

# The reference machine (control/include/ctl_machine.h, host_sim/plant/plant.c).
REF = {"r": 2.0, "ld": 0.035, "lq": 0.055, "lxy": 0.010, "psi": 0.225, "pp": 3, "j": 0.01,
       "b": 0.001}

# quantity in metrics.json, column title, limit: (relative, absolute) - a result passes either
QUANTITIES = (
    ("r", "R", (0.02, None)),
    ("ld", "L_d", (0.03, None)),
    ("lq", "L_q", (0.03, None)),
    ("lxy", "L_xy", (0.05, None)),
    ("psi_f", "psi_f", (0.02, None)),
    ("encoder_offset", "offset", (None, 1.0)),
    ("inertia", "J", (0.05, None)),
    ("friction", "B", (0.20, 2e-4)),
)


def machine(name, **over):
    m = dict(REF)
    m.update(over)
    return (name, m)


# Each axis of the range at both ends (the others at the reference), then combined corners.
MACHINES = (
    machine("reference"),
    machine("R 1 ohm", r=1.0),
    machine("R 4 ohm", r=4.0),
    machine("L_d, L_q 0.6 x", ld=0.6 * REF["ld"], lq=0.6 * REF["lq"]),
    machine("L_d, L_q 1.6 x", ld=1.6 * REF["ld"], lq=1.6 * REF["lq"]),
    machine("saliency 1.0 (L_d = L_q)", ld=0.6 * REF["ld"], lq=0.6 * REF["ld"]),
    machine("saliency 2.5", ld=0.6 * REF["ld"], lq=1.5 * REF["ld"]),
    machine("L_xy 0.3 x", lxy=0.3 * REF["lxy"]),
    machine("L_xy 3 x", lxy=3.0 * REF["lxy"]),
    machine("psi_f 0.3 x", psi=0.3 * REF["psi"]),
    machine("psi_f 1.5 x", psi=1.5 * REF["psi"]),
    machine("2 pole pairs", pp=2),
    machine("6 pole pairs", pp=6),
    machine("J 0.2 x", j=0.2 * REF["j"]),
    machine("J 10 x", j=10.0 * REF["j"]),
    machine("no friction", b=0.0),
    machine("friction 10 x", b=10.0 * REF["b"]),
    machine("R 4 ohm, L_xy 0.3 x (issue 25)", r=4.0, lxy=0.3 * REF["lxy"]),
    machine("R 4, L 0.6 x, L_xy 0.3 x, psi_f 0.3 x", r=4.0, ld=0.6 * REF["ld"],
            lq=0.6 * REF["lq"], lxy=0.3 * REF["lxy"], psi=0.3 * REF["psi"]),
    machine("R 1, L 1.6 x, L_xy 3 x, psi_f 1.5 x", r=1.0, ld=1.6 * REF["ld"],
            lq=1.6 * REF["lq"], lxy=3.0 * REF["lxy"], psi=1.5 * REF["psi"]),
    machine("6 pole pairs, psi_f 1.5 x, J 10 x", pp=6, psi=1.5 * REF["psi"], j=10.0 * REF["j"]),
    machine("2 pole pairs, psi_f 0.3 x, J 0.2 x, friction 10 x", pp=2, psi=0.3 * REF["psi"],
            j=0.2 * REF["j"], b=10.0 * REF["b"]),
    # the five plants of tests/sim/test_sim_commission.c, with their encoder offsets and seeds
    machine("test plant 1: R -40 %, L_d +30 %, L_q -30 %", r=1.2, ld=0.0455, lq=0.0385,
            lxy=0.008, psi=0.26, offset=37.0, seed=1),
    machine("test plant 2: R +40 %, L_xy +30 %, psi_f -30 %", r=2.8, ld=0.0245, lq=0.0715,
            lxy=0.013, psi=0.1575, offset=123.0, seed=2),
    machine("test plant 3: L_xy -30 %, psi_f +30 %", r=1.2, ld=0.040, lq=0.060, lxy=0.007,
            psi=0.2925, offset=-70.0, seed=5),
    machine("test plant 4: L_q +30 %", r=2.4, ld=0.030, lq=0.0715, lxy=0.012, psi=0.20,
            offset=200.0, seed=7),
    machine("test plant 5: L_d and L_q -30 %", r=1.6, ld=0.0245, lq=0.0385, lxy=0.009, psi=0.25,
            offset=301.0, seed=3),
)


# The results outside the limits today, "machine | arithmetic | column" per line: open work of
# issue 25, kept visible in the table; a new failure, or a listed one that passes, fails the check.
KNOWN_FILE = os.path.join(HERE, "commission_grid_known.txt")


def known_outside():
    with open(KNOWN_FILE, encoding="utf-8") as f:
        return frozenset(tuple(part.strip() for part in line.split("|"))
                         for line in f if line.strip() and not line.startswith("#"))


def sim_args(m):
    a = ["--motor-r", repr(m["r"]), "--motor-ld", repr(m["ld"]), "--motor-lq", repr(m["lq"]),
         "--motor-lxy", repr(m["lxy"]), "--motor-psi-f", repr(m["psi"]),
         "--motor-pole-pairs", str(m["pp"]), "--ctl-pole-pairs", str(m["pp"])]
    a += ["--motor-j", repr(m["j"]), "--motor-b", repr(m["b"])]
    if "offset" in m:
        a += ["--encoder-offset-deg", repr(m["offset"])]
    if "seed" in m:
        a += ["--seed", str(m["seed"])]
    return a


def run_one(sim, m, arith):
    return sim_doc_table.run_json(sim, ["--controller", "ddc", "--scenario", "commission",
                                        "--arith", arith] + sim_args(m))["commission"]


def judge(c, key, limit):
    """(cell text, passes) of one quantity."""
    r = c["results"].get(key)
    if r is None:
        return None, True
    if r["quality"] != "ok" or r.get("identified") is None:
        return "%s (%s)" % (r["quality"], r["reason"]), False
    rel_lim, abs_lim = limit
    if "error_deg" in r:
        err, sigma, abs_err, rel = r["error_deg"], r["sigma"], abs(r["error_deg"]), None
        text = "%+.2f deg (%.2f)" % (err, sigma)
    elif r["true"] == 0:
        err = r["identified"]
        sigma, abs_err, rel = r["sigma"], abs(err), None
        text = "%+.1e (%.1e)" % (err, sigma)
    else:
        true = r["true"]
        err = 100.0 * (r["identified"] - true) / true
        sigma = 100.0 * r["sigma"] / abs(true)
        abs_err, rel = abs(r["identified"] - true), abs(err) / 100.0
        text = "%+.2f %% (%.2f)" % (err, sigma)
    within = ((rel_lim is not None and rel is not None and rel <= rel_lim) or
              (abs_lim is not None and abs_err <= abs_lim))
    ok = within and abs(err) <= SIGMAS * sigma
    return (text if ok else "**" + text + "**"), ok


def table(sim, jobs):
    quantities = QUANTITIES
    runs = [(name, m, a) for name, m in MACHINES for a in ARITHS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        results = list(pool.map(lambda r: run_one(sim, r[1], r[2]), runs))
    head = "| machine | arithmetic | sequence | " + " | ".join(
        "%s error (sigma)" % q[1] for q in quantities) + " |"
    lines = [head, "|" + "---|" * (3 + len(quantities))]
    failures = []
    for (name, _, arith), c in zip(runs, results):
        cells = []
        for key, title, limit in quantities:
            text, ok = judge(c, key, limit)
            cells.append("n/a" if text is None else text)
            if not ok:
                failures.append(((name, arith, title), text))
        if c["state"] != "done":
            failures.append(((name, arith, "sequence"), "%s (%s)" % (c["state"], c["reason"])))
        lines.append("| %s | %s | %s | %s |" % (name, arith, c["state"], " | ".join(cells)))
    results = len(runs) * len(quantities) + len(runs)
    lines.append("")
    lines.append("%d runs; %d of %d results (every quantity and the sequence of every run) outside "
                 "the limits, each on the list of known ones (tools/commission_grid_known.txt)." %
                 (len(runs), len(failures), results))
    return "\n".join(lines) + "\n", failures, len(runs)


def main():
    ap = sim_doc_table.parser(__doc__.splitlines()[0], "docs/commissioning.md")
    ap.add_argument("--write-known", action="store_true",
                    help="with --write: record today's results outside the limits as the known ones")
    a = ap.parse_args()
    if a.write_known and not a.write:
        print("commission_grid: --write-known needs --write", file=sys.stderr)
        return 1
    if not sim_doc_table.usable("commission_grid", a):
        return 1
    if len({name for name, _ in MACHINES}) != len(MACHINES):
        print("commission_grid: two machines share a name", file=sys.stderr)
        return 1
    block, failures, runs = table(a.sim, a.jobs)
    status = sim_doc_table.update_block("commission_grid", DOC, BEGIN, END, block, a)
    failed = {key for key, _ in failures}
    known = known_outside()
    if a.write_known:
        with open(KNOWN_FILE, "w", encoding="utf-8") as f:
            f.write("# Written by tools/commission_grid.py --write --write-known: the results outside the\n"
                    "# limits (open work of issue 25). One per line: machine | arithmetic | column.\n")
            for key in sorted(failed):
                f.write(" | ".join(key) + "\n")
        known = frozenset(failed)
    for key, text in failures:
        if key not in known:
            print("commission_grid: outside the limits: %s, %s: %s %s" % (key + (text,)),
                  file=sys.stderr)
            status = 1
    for key in sorted(known - failed):
        print("commission_grid: %s, %s: %s now within the limits; take it off %s" % (key + (os.path.basename(KNOWN_FILE),)),
              file=sys.stderr)
        status = 1
    print("commission_grid: %d runs, %d results outside the limits (%d known)" %
          (runs, len(failures), len(failed & known)))
    return status


if __name__ == "__main__":
    sys.exit(main())
