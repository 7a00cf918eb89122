#!/usr/bin/env python3
"""Plots for `sixphase-sim reproduce` (called by it with the output directory and the part
`traces-then-summary`: the runs' figures while its last runs compute, the summary's once it
closes this script's standard input).

Figures in the style of the paper's: phase currents, x-y currents, torque and
speed, conventional MPTC-49 beside the discrete-duty method (DDC).
Reads DIR/runs/<case>/trace.csv (one row per control period) and
DIR/summary.json; writes DIR/plots/*.png.
"""
import json
import multiprocessing
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import plot_postfault  # noqa: E402  (beside this script)

# trace.csv columns (see host_sim/run/sim.c)
T, SPEED, IA, IB, IC, IX, IY, TE, TREF = 0, 1, 3, 4, 5, 11, 12, 13, 16
USECOLS = tuple(range(0, 18))
PROCESSES = 2  # drawing processes
# what to draw: the runs' traces, summary.json's figures, or the traces and then, once its
# standard input closes (the caller has written summary.json), the summary's
PARTS = ("traces", "summary", "traces-then-summary")

PAPER = {
    "lambda": [20, 100, 200],
    "thd_mptc": [43.5, 28.6, 52.5],
    "thd_ddc": [13.5, 13.0, 12.8],
    "rip_mptc": [0.42, 0.58, 0.89],
    "rip_ddc": [0.29, 0.31, 0.58],
}


def load(run_dir):
    path = os.path.join(run_dir, "trace.csv")
    if not os.path.exists(path):
        return None
    return np.loadtxt(path, delimiter=",", skiprows=1, usecols=USECOLS)


def panel_column(axes, d, title, t_from=None, t_to=None):
    t = d[:, T]
    m = np.ones_like(t, dtype=bool)
    if t_from is not None:
        m &= t >= t_from
    if t_to is not None:
        m &= t <= t_to
    tm = t[m] * 1e3
    ax = axes[0]
    for col, lab in ((IA, "i_A"), (IB, "i_B"), (IC, "i_C")):
        ax.plot(tm, d[m, col], lw=0.7, label=lab)
    ax.set_ylabel("phase current (A)")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=7, ncol=3)
    ax = axes[1]
    ax.plot(tm, d[m, IX], lw=0.7, label="i_x")
    ax.plot(tm, d[m, IY], lw=0.7, label="i_y")
    ax.set_ylabel("x-y current (A)")
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    ax = axes[2]
    ax.plot(tm, d[m, TE], lw=0.6, label="T_e (plant)")
    ax.plot(tm, d[m, TREF], lw=0.8, label="T_ref", alpha=0.8)
    ax.set_ylabel("torque (N m)")
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    ax = axes[3]
    ax.plot(tm, d[m, SPEED], lw=0.8)
    ax.set_ylabel("speed (r/min)")
    ax.set_xlabel("time (ms)")
    for a in axes:
        a.grid(True, lw=0.3)


def comparison(runs, left, right, out, title, window=None, share_current=True):
    dl = load(os.path.join(runs, left))
    dr = load(os.path.join(runs, right))
    if dl is None or dr is None:
        return
    fig, axes = plt.subplots(4, 2, figsize=(11, 9), sharex="col")
    t_from = t_to = None
    if window is not None:
        t_end = min(dl[-1, T], dr[-1, T])
        t_from, t_to = t_end - window, t_end
    panel_column(axes[:, 0], dl, "conventional MPTC-49", t_from, t_to)
    panel_column(axes[:, 1], dr, "discrete-duty MPTC (DDC)", t_from, t_to)
    for row in range(4):
        lo = min(axes[row, 0].get_ylim()[0], axes[row, 1].get_ylim()[0])
        hi = max(axes[row, 0].get_ylim()[1], axes[row, 1].get_ylim()[1])
        if row != 0 or share_current:
            axes[row, 0].set_ylim(lo, hi)
            axes[row, 1].set_ylim(lo, hi)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def lambda_sweep(summary, out):
    by = {s["name"]: s for s in summary if s.get("ok")}
    lam = PAPER["lambda"]

    def series(prefix, key):
        vals = [by.get(f"{prefix}_l{l}", {}).get(key) for l in lam]
        return [np.nan if v is None else v for v in vals]

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    ax = axes[0]
    ax.plot(lam, series("steady_mptc49", "thd_percent"), "o-", label="MPTC-49 (sim)")
    ax.plot(lam, series("steady_ddc", "thd_percent"), "s-", label="DDC (sim)")
    ax.plot(lam, series("steady_mptc13", "thd_percent"), "^-", color="C2", label="MPTC-13 (sim)")
    ax.plot(lam, series("steady_ddc", "thd_h50_percent"), "s:", color="C1", label="DDC (sim), harmonics 2..50")
    ax.plot(lam, series("guard_ddc", "thd_percent"), "D-", color="C3", label="DDC + torque guard (sim)")
    ax.plot(lam, PAPER["thd_mptc"], "o--", color="C0", alpha=0.5, label="MPTC (paper)")
    ax.plot(lam, PAPER["thd_ddc"], "s--", color="C1", alpha=0.5, label="proposed (paper)")
    ax.set_xlabel("lambda (N m/Wb)")
    ax.set_ylabel("phase-current THD (%)")
    ax.set_yscale("log")
    ax.legend(fontsize=7)
    ax.grid(True, lw=0.3, which="both")
    ax = axes[1]
    ax.plot(lam, series("steady_mptc49", "torque_ripple_nm"), "o-", label="MPTC-49 (sim)")
    ax.plot(lam, series("steady_ddc", "torque_ripple_nm"), "s-", label="DDC (sim)")
    ax.plot(lam, series("steady_mptc13", "torque_ripple_nm"), "^-", color="C2", label="MPTC-13 (sim)")
    ax.plot(lam, series("guard_ddc", "torque_ripple_nm"), "D-", color="C3", label="DDC + torque guard (sim)")
    ax.plot(lam, PAPER["rip_mptc"], "o--", color="C0", alpha=0.5, label="MPTC (paper)")
    ax.plot(lam, PAPER["rip_ddc"], "s--", color="C1", alpha=0.5, label="proposed (paper)")
    ax.set_xlabel("lambda (N m/Wb)")
    ax.set_ylabel("torque ripple, std (N m)")
    ax.legend(fontsize=7)
    ax.grid(True, lw=0.3)
    fig.suptitle("Steady state, 1500 r/min, rated load, 10 kHz")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def figure_jobs(base, part):
    """The figures to draw: (function, arguments) each, independent of each other. part
    "traces": those of the runs' traces only (reproduce draws them while its later runs
    compute); "summary": those of summary.json only; None: all."""
    runs = os.path.join(base, "runs")
    plots = os.path.join(base, "plots")
    jobs = []
    for lam in (20, 100, 200):
        jobs.append((comparison, (runs, f"steady_mptc49_l{lam}", f"steady_ddc_l{lam}",
                                  os.path.join(plots, f"steady_l{lam}.png"),
                                  f"Steady state 1500 r/min, rated load, lambda = {lam} (last 40 ms)",
                                  0.04, False)))
    jobs.append((comparison, (runs, "accel_mptc49", "accel_ddc", os.path.join(plots, "accel.png"),
                              "Acceleration 0 -> 800 r/min, no load")))
    jobs.append((comparison, (runs, "reversal_mptc49", "reversal_ddc",
                              os.path.join(plots, "reversal.png"),
                              "Reversal 800 -> -800 r/min, no load")))
    jobs.append((comparison, (runs, "load-step_mptc49", "load-step_ddc",
                              os.path.join(plots, "load-step.png"), "Rated load step at 1500 r/min")))
    jobs.append((plot_postfault.plots, (runs, plots)))  # section 9's figures (open phase)
    if part == "summary":
        jobs = []
    summ = os.path.join(base, "summary.json")
    if part != "traces" and os.path.exists(summ):
        with open(summ) as f:
            jobs.append((lambda_sweep, (json.load(f), os.path.join(plots, "lambda_sweep.png"))))
    return jobs


def draw(job):
    fn, args = job
    fn(*args)


def main():
    """Draws the figures in two processes (forked after matplotlib is imported, so neither pays
    the import again): most of the time goes into laying out and rendering them, which a 2-core
    machine then does in about half the wall time."""
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] not in PARTS):
        print("usage: plot_reproduce.py DIR [%s]" % "|".join(PARTS), file=sys.stderr)
        return 2
    base = sys.argv[1]
    part = sys.argv[2] if len(sys.argv) == 3 else None
    os.makedirs(os.path.join(base, "plots"), exist_ok=True)
    gated = part == "traces-then-summary"
    stages = [figure_jobs(base, "traces"), None] if gated else [figure_jobs(base, part)]
    try:
        ctx = multiprocessing.get_context("fork")
    except ValueError:  # no fork on this platform: one process
        ctx = None
    pool = ctx.Pool(PROCESSES) if ctx is not None else None
    for jobs in stages:
        if jobs is None:  # the gate: summary.json is complete when stdin closes
            sys.stdin.read()
            jobs = figure_jobs(base, "summary")
        if pool is None:
            for job in jobs:
                draw(job)
        else:
            pool.map(draw, jobs, chunksize=1)
    if pool is not None:
        pool.close()
        pool.join()
    return 0


if __name__ == "__main__":
    sys.exit(main())
