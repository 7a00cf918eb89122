#!/usr/bin/env python3
"""The figure of one `sixphase-sim run --pil TARGET --out DIR` (DIR/pil.csv): the target's count
for each control period over the run (the whole ISR, and the stack of its stages), and their
histogram in RUN. Writes DIR/pil.png (1000 x 900 pixels).
usage: plot_pil.py DIR"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RUN = 3  # the drive's RUN state (firmware/app/lists/drive_states.h)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_pil.py DIR")
    path = os.path.join(sys.argv[1], "pil.csv")
    if not os.path.exists(path):
        sys.exit("plot_pil.py: %s not found (the run needs --pil and --out)" % path)
    with open(path) as f:
        reader = csv.DictReader(f)
        rows = list(reader)
    if len(rows) < 2:
        sys.exit("plot_pil.py: %s holds no periods" % path)
    # the stages are pil.csv's columns between the whole ISR's and the comparison's
    stages = reader.fieldnames[reader.fieldnames.index("cycles") + 1:
                               reader.fieldnames.index("agrees")]
    t = [float(r["t_s"]) for r in rows]
    total = [float(r["cycles"]) for r in rows]
    fig, axs = plt.subplots(3, 1, figsize=(10, 9))
    axs[0].plot(t, total, lw=0.6)
    axs[0].set_ylabel("ISR, counter ticks")
    axs[0].set_title("the target's count per control period")
    bottom = [0.0] * len(rows)
    for name in stages:
        v = [float(r[name]) for r in rows]
        axs[1].fill_between(t, bottom, [b + x for b, x in zip(bottom, v)], step="post",
                            label=name, lw=0)
        bottom = [b + x for b, x in zip(bottom, v)]
    axs[1].set_ylabel("stages, counter ticks")
    axs[1].legend(loc="upper left", ncol=6, fontsize=8)
    running = [c for c, r in zip(total, rows) if int(r["state"]) == RUN]
    axs[2].hist(running or total, bins=40)
    axs[2].set_xlabel("ISR, counter ticks (periods in RUN)" if running else "ISR, counter ticks")
    axs[2].set_ylabel("periods")
    for ax in axs[:2]:
        ax.set_xlabel("time (s)")
    bad = [x for x, r in zip(t, rows) if r["agrees"] != "1"]
    if bad:
        axs[0].plot(bad, [max(total)] * len(bad), "r|", label="differs from the host")
        axs[0].legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(sys.argv[1], "pil.png"), dpi=100)


if __name__ == "__main__":
    main()
