#!/usr/bin/env python3
"""Plot a capture written by `sixphase-link capture --out FILE.csv`: one panel per channel
against time from the trigger. usage: plot_capture.py FILE.csv OUT.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_capture.py FILE.csv OUT.png")
    with open(sys.argv[1]) as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        sys.exit("plot_capture.py: %s holds no samples" % sys.argv[1])
    head, data = rows[0], [[float(x) for x in r] for r in rows[1:]]
    t = [r[0] * 1e3 for r in data]
    fig, axes = plt.subplots(len(head) - 1, 1, sharex=True, squeeze=False,
                             figsize=(8, 2.2 * (len(head) - 1)))
    for k, name in enumerate(head[1:], start=1):
        ax = axes[k - 1][0]
        ax.plot(t, [r[k] for r in data], lw=0.8)
        ax.set_ylabel(name.replace("_", " ", 1))
        ax.axvline(0.0, color="grey", lw=0.5)
        ax.grid(True, lw=0.3)
    axes[-1][0].set_xlabel("time from trigger (ms)")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=100)


if __name__ == "__main__":
    main()
