#!/usr/bin/env python3
"""Plots of a `sixphase-sim sweep` (DIR/sweep.csv): each metric against the first swept
option, one line per combination of the other swept options, in DIR/plots/<metric>.png; and
DIR/plots/tradeoff.png: six-phase THD and torque ripple against switching frequency, the
Pareto front (no other point lower in both the metric and the switching frequency) marked.
usage: plot_sweep.py DIR"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METRICS = ["thd_percent", "thd50_percent", "torque_ripple_nm", "torque_ripple_pp_nm",
           "torque_mean_nm", "speed_mean_rpm", "xy_current_rms_a", "switching_freq_hz",
           "phase_current_peak_a", "transient_ms"]


def number(x):
    try:
        return float(x)
    except ValueError:
        return None


def pareto(points):
    """Indices of the points no other point beats in both coordinates (lower is better)."""
    front = []
    for i, (x, y) in enumerate(points):
        if not any(x2 <= x and y2 <= y and (x2, y2) != (x, y) for x2, y2 in points):
            front.append(i)
    return front


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_sweep.py DIR")
    base = sys.argv[1]
    with open(os.path.join(base, "sweep.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("plot_sweep.py: no rows in %s/sweep.csv" % base)
    fields = list(rows[0].keys())
    axes = fields[1:fields.index(METRICS[0])]
    out = os.path.join(base, "plots")
    os.makedirs(out, exist_ok=True)
    x_axis, others = axes[0], axes[1:]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[a] for a in others), []).append(r)
    numeric_x = all(number(r[x_axis]) is not None for r in rows)
    for m in METRICS:
        fig, ax = plt.subplots(figsize=(7, 4))
        for key, rs in groups.items():
            pts = [(number(r[x_axis]) if numeric_x else r[x_axis], number(r[m])) for r in rs]
            pts = [p for p in pts if p[1] is not None]
            if pts:
                label = ", ".join("%s %s" % (a, v) for a, v in zip(others, key)) or None
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, label=label)
        ax.set_xlabel(x_axis)
        ax.set_ylabel(m)
        ax.grid(True, lw=0.3)
        if others and ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, m + ".png"), dpi=90)
        plt.close(fig)
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    for ax, m in zip(axs, ["thd_percent", "torque_ripple_nm"]):
        pts = [(number(r["switching_freq_hz"]), number(r[m])) for r in rows]
        pts = [p for p in pts if p[0] is not None and p[1] is not None]
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=10, label="runs")
        front = sorted(pts[i] for i in pareto(pts))
        ax.plot([p[0] for p in front], [p[1] for p in front], color="red", marker="o", ms=4,
                label="Pareto front")
        ax.set_xlabel("switching frequency (Hz)")
        ax.set_ylabel(m)
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tradeoff.png"), dpi=90)


if __name__ == "__main__":
    main()
