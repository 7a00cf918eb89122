#!/usr/bin/env python3
"""The figure of one `sixphase-sim run --out DIR` (DIR/trace.csv), laid out like the paper's
waveform figures: speed over the whole run, and over the last 50 ms the six phase currents,
the d-q and x-y currents, torque with its reference, stator flux with its reference, and the
switching state with its duty. Writes DIR/run.png (1000 x 1400 pixels).
usage: plot_run.py DIR"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TAIL_S = 0.05


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_run.py DIR")
    path = os.path.join(sys.argv[1], "trace.csv")
    if not os.path.exists(path):
        sys.exit("plot_run.py: %s not found (the run needs --out and its trace)" % path)
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if len(rows) < 2:
        sys.exit("plot_run.py: %s holds no periods" % path)
    col = {k: [float(r[k]) for r in rows] for k in rows[0] if k != "legs"}
    t = col["t"]
    first = next(i for i, x in enumerate(t) if x >= t[-1] - TAIL_S)
    tail = [x * 1e3 for x in t[first:]]
    fig, axs = plt.subplots(7, 1, figsize=(10, 14))
    axs[0].plot(t, col["speed_rpm"], lw=0.8)
    axs[0].set_ylabel("speed r/min")
    axs[0].set_xlabel("time (s), whole run")
    panels = [
        (["i_A", "i_B", "i_C", "i_D", "i_E", "i_F"], "phase currents A"),
        (["i_d", "i_q"], "d-q currents A"),
        (["i_x", "i_y"], "x-y currents A"),
        (["Te", "Te_avg", "Tref"], "torque N m"),
        (["psi_s", "psi_ref"], "stator flux Wb"),
        (["vector", "duty"], "state / duty"),
    ]
    for ax, (names, label) in zip(axs[1:], panels):
        for n in names:
            y = col[n][first:]
            if n == "duty":
                ax2 = ax.twinx()
                ax2.step(tail, y, where="post", color="tab:red", lw=0.6, label=n)
                ax2.set_ylabel("duty", color="tab:red")
                continue
            drawn = ax.step if n == "vector" else ax.plot
            drawn(tail, y, lw=0.7, label=n)
        ax.set_ylabel(label)
        ax.legend(fontsize=7, loc="upper right", ncol=3)
        ax.grid(True, lw=0.3)
    axs[-1].set_xlabel("time (ms), last %.0f ms" % (TAIL_S * 1e3))
    fig.tight_layout()
    fig.savefig(os.path.join(sys.argv[1], "run.png"), dpi=100)


if __name__ == "__main__":
    main()
