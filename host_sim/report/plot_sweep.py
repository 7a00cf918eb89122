#!/usr/bin/env python3
"""Plots of a `sixphase-sim sweep` (DIR/sweep.csv, columns in host_sim/sweep/sweep_table.h).

Only the points whose outcome is "ok" are drawn: a point the drive stopped in a fault has the
metrics of a stopped drive (no ripple, no switching) and a failed run has none.

DIR/plots/<metric>.png: each metric against the first swept option (the first "--OPTION"
column whose value changes), one line per combination of the other swept options.
DIR/plots/tradeoff.png: six-phase THD and torque ripple against switching frequency, the
Pareto front (no other point lower in both) marked; DIR/plots/pareto.csv lists its points.
usage: plot_sweep.py DIR"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The metrics drawn (metrics.json names); the table has more.
PLOTTED = ["thd_percent", "thd_h50_percent", "torque_ripple_nm", "torque_ripple_pp_nm",
           "torque_ripple_sampled_nm", "torque_mean_nm", "speed_mean_rpm", "xy_current_rms_a",
           "phase_current_rms_a", "switching_freq_hz", "phase_current_peak_a",
           "adc_clipped_samples", "transient_ms"]
TRADEOFF = ["thd_percent", "torque_ripple_nm"]


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


def swept_axes(fields, rows):
    """The option columns whose value changes, in table order (the first is the x axis)."""
    options = [f for f in fields if f.startswith("--")]
    axes = [o for o in options if len({r[o] for r in rows}) > 1]
    return axes or options[:1]


def note_left_out(ax, good, rows):
    left = len(rows) - len(good)
    if not good:
        ax.text(0.5, 0.5, "no point without a drive fault or a failed run", ha="center",
                transform=ax.transAxes)
    if left:
        ax.set_title("%d of %d points left out (drive fault or failed run)" % (left, len(rows)),
                     fontsize=8)


def metric_plot(out, m, good, rows, x_axis, others):
    numeric_x = all(number(r[x_axis]) is not None for r in good)
    groups = {}
    for r in good:
        groups.setdefault(tuple(r[a] for a in others), []).append(r)
    fig, ax = plt.subplots(figsize=(7, 4))
    for key, rs in groups.items():
        pts = [(number(r[x_axis]) if numeric_x else r[x_axis], number(r[m])) for r in rs]
        pts = [p for p in pts if p[1] is not None]
        if pts:
            label = ", ".join("%s %s" % (a[2:], v) for a, v in zip(others, key)) or None
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, label=label)
    ax.set_xlabel(x_axis[2:])
    ax.set_ylabel(m)
    ax.grid(True, lw=0.3)
    note_left_out(ax, good, rows)
    if others and ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, m + ".png"), dpi=90)
    plt.close(fig)


def tradeoff_plot(out, good, rows):
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    with open(os.path.join(out, "pareto.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["metric", "point", "switching_freq_hz", "value"])
        for ax, m in zip(axs, TRADEOFF):
            pts = [(number(r["switching_freq_hz"]), number(r[m]), r["point"]) for r in good]
            pts = [p for p in pts if p[0] is not None and p[1] is not None]
            note_left_out(ax, good, rows)
            ax.set_xlabel("switching frequency (Hz)")
            ax.set_ylabel(m)
            ax.grid(True, lw=0.3)
            if not pts:
                continue
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=10, label="runs")
            front = sorted(pts[i] for i in pareto([(p[0], p[1]) for p in pts]))
            ax.plot([p[0] for p in front], [p[1] for p in front], color="red", marker="o", ms=4,
                    label="Pareto front")
            ax.legend(fontsize=7)
            for x, y, point in front:
                w.writerow([m, point, "%g" % x, "%g" % y])
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tradeoff.png"), dpi=90)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_sweep.py DIR")
    base = sys.argv[1]
    with open(os.path.join(base, "sweep.csv")) as f:
        reader = csv.DictReader(f)
        fields = reader.fieldnames or []
        rows = list(reader)
    if not rows or "outcome" not in fields:
        sys.exit("plot_sweep.py: no rows in %s/sweep.csv" % base)
    good = [r for r in rows if r["outcome"] == "ok"]
    axes = swept_axes(fields, rows)
    out = os.path.join(base, "plots")
    os.makedirs(out, exist_ok=True)
    for m in PLOTTED:
        if m in fields:
            metric_plot(out, m, good, rows, axes[0], axes[1:])
    tradeoff_plot(out, good, rows)


if __name__ == "__main__":
    main()
