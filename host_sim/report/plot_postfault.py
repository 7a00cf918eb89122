"""Open-phase plots for `sixphase-sim reproduce` (plot_reproduce.py calls plots()).

Reads DIR/runs/pf_*/trace.csv (one row per control period) and writes DIR/plots/postfault_*.png:
the phase currents, torque and speed through an open phase in C with the drive stopping and
riding through, the two post-fault strategies, rated load, and an isolation command on a
connected phase.
"""
import os

import matplotlib.pyplot as plt
import numpy as np

# trace.csv columns (host_sim/record/recorder.c)
T, SPEED, PHASES, TE, TREF = 0, 1, range(3, 9), 13, 16
NAMES = "ABCDEF"


def _load(runs, name):
    path = os.path.join(runs, name, "trace.csv")
    if not os.path.exists(path):
        return None
    return np.loadtxt(path, delimiter=",", skiprows=1, usecols=tuple(range(0, 18)))


def _window(d, t0, t1):
    m = (d[:, T] >= t0) & (d[:, T] <= t1)
    return d[m]


def _currents(ax, d, title):
    for k, col in enumerate(PHASES):
        ax.plot(d[:, T] * 1e3, d[:, col], lw=0.6, label="i_" + NAMES[k])
    ax.set_ylabel("phase current (A)")
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper right", fontsize=6, ncol=6)
    ax.grid(True, lw=0.3)


def _torque(ax, d):
    ax.plot(d[:, T] * 1e3, d[:, TE], lw=0.5, label="T_e (plant)")
    ax.plot(d[:, T] * 1e3, d[:, TREF], lw=0.8, label="T_ref")
    ax.set_ylabel("torque (N m)")
    ax.legend(loc="upper right", fontsize=6, ncol=2)
    ax.grid(True, lw=0.3)


def _speed(ax, d):
    ax.plot(d[:, T] * 1e3, d[:, SPEED], lw=0.8)
    ax.set_ylabel("speed (r/min)")
    ax.set_xlabel("time (ms)")
    ax.grid(True, lw=0.3)


def _through_the_fault(runs, out):
    stop, ride = _load(runs, "pf_stop_C"), _load(runs, "pf_ride_C")
    if stop is None or ride is None:
        return
    fig, axes = plt.subplots(3, 2, figsize=(12, 8), sharex="col")
    for col, (d, title) in enumerate(((stop, "stop (build default)"),
                                      (ride, "ride-through (--ride-through)"))):
        w = _window(d, 0.23, 0.36)
        _currents(axes[0, col], w, "phase C opens at 250 ms, " + title)
        _torque(axes[1, col], w)
        _speed(axes[2, col], w)
    fig.suptitle("Open phase C at 1500 r/min, 3.5 N m (DDC): detected at 320 ms")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def _strategies(runs, out):
    ml, mt = _load(runs, "pf_ride_C"), _load(runs, "pf_ride_C_mt")
    if ml is None or mt is None:
        return
    fig, axes = plt.subplots(2, 2, figsize=(12, 6), sharex="col")
    for col, (d, title) in enumerate(((ml, "minimum loss (default)"),
                                      (mt, "maximum torque (--postfault max-torque)"))):
        w = _window(d, d[-1, T] - 0.04, d[-1, T])
        _currents(axes[0, col], w, "five legs, phase C open: " + title)
        _torque(axes[1, col], w)
        axes[1, col].set_xlabel("time (ms)")
    fig.suptitle("Post-fault currents, last 40 ms (1500 r/min, 3.5 N m)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def _rated(runs, out):
    ride, rated = _load(runs, "pf_ride_C"), _load(runs, "pf_rated_C")
    if ride is None or rated is None:
        return
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for d, lab in ((ride, "3.5 N m load"), (rated, "rated 7 N m load")):
        axes[0].plot(d[:, T] * 1e3, d[:, SPEED], lw=0.8, label=lab)
        axes[1].plot(d[:, T] * 1e3, d[:, TREF], lw=0.8, label="T_ref, " + lab)
    axes[0].set_ylabel("speed (r/min)")
    axes[0].legend(fontsize=7)
    axes[1].set_ylabel("torque reference (N m)")
    axes[1].set_xlabel("time (ms)")
    axes[1].legend(fontsize=7)
    for a in axes:
        a.grid(True, lw=0.3)
    fig.suptitle("Ride-through of phase C at 0.32 s: the derated limit (4.66 N m) against the load")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def _isolation(runs, out):
    d = _load(runs, "pf_isolate_C")
    if d is None:
        return
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    w = _window(d, d[-1, T] - 0.04, d[-1, T])
    _currents(axes[0], w, "leg C isolated by command, phase C still connected: its diodes conduct")
    _torque(axes[1], w)
    axes[1].set_xlabel("time (ms)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def plots(runs, plots_dir):
    _through_the_fault(runs, os.path.join(plots_dir, "postfault_C.png"))
    _strategies(runs, os.path.join(plots_dir, "postfault_strategies.png"))
    _rated(runs, os.path.join(plots_dir, "postfault_rated.png"))
    _isolation(runs, os.path.join(plots_dir, "postfault_isolation.png"))
