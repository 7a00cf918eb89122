#!/usr/bin/env python3
"""Input records for tools/avr_proxy/replay.c, built from sixphase-sim traces.

Records the traces with the simulator (at run time, nothing large is committed), then writes
one input stream per arithmetic: the same records, with every ctl_q as the bit pattern of that
build (Q24 int32 for fixed, IEEE single for float). The record format is described at the top
of replay.c.

usage: gen_inputs.py --sim PATH --work DIR --out-fixed FILE --out-float FILE [--scale X]
"""
import argparse
import csv
import math
import os
import struct
import subprocess
import sys

I_BASE = 10.0
V_BASE = 540.0
W_BASE = 942.47779607693797
T_BASE = 17.188733853924696
POLE_PAIRS = 3
VDC_V = 540.0

DDC, MPTC49, MPTC13, FOC = 0, 1, 2, 3
VVMPTC = 4  # CTL_CONTROLLER_VVMPTC (its id in ctl_params.h's CTL_CONTROLLER_LIST)
FLUX_ERROR, XY_TABLE = 0, 1
CONSTANT, MTPA = 0, 1
SPEED, TORQUE = 0, 1

# flags of a step record
F_PROTECT, F_ENC_OK, F_OVERRUN, F_HW_TRIP, F_RUNNING, F_CALIBRATED = 1, 2, 4, 8, 16, 32
F_NORMAL = F_PROTECT | F_ENC_OK | F_RUNNING | F_CALIBRATED


def params(controller=DDC, direction=FLUX_ERROR, guard=True, flux_mode=MTPA, levels=6,
           lam=100.0, tlim=7.0, kp=1.5, ki=60.0, flux_wb=0.26, ts=1e-4, oc=15.0, os_rpm=2000.0,
           ov=720.0, mid=False, fewest=True, tie=True, per_set=True, open_phase=-1, strategy=0):
    """The improvement flags in one byte: bit 0 torque guard, 1 mid-period angle, 2 fewest
    transitions, 3 flux tie band off, 4 each three-phase set's zero state on its own (with
    bit 2; guard=False alone is the paper's DDC only with fewest=False and tie=False too); the
    open phase as leg + 1 (0: none)."""
    flags = ((1 if guard else 0) | (2 if mid else 0) | (4 if fewest else 0) |
             (0 if tie else 8) | (16 if fewest and per_set else 0))
    return (struct.pack("<BBBBh", controller, direction, flags, flux_mode, levels) +
            struct.pack("<9f", lam, tlim, kp, ki, flux_wb, ts, oc, os_rpm, ov) +
            struct.pack("<BB", open_phase + 1, strategy))


class Stream:
    """Builds both arithmetic streams at once."""

    def __init__(self):
        self.fixed = bytearray()
        self.float = bytearray()
        self.steps = 0
        self.counts = {}

    def raw(self, b):
        self.fixed += b
        self.float += b

    def q(self, x):
        v = int(math.floor(x * 16777216.0 + 0.5))
        v = max(-2**31, min(2**31 - 1, v))
        self.fixed += struct.pack("<i", v)
        self.float += struct.pack("<f", x)

    def init(self, **kw):
        self.raw(b"N" + params(**kw))

    def request(self, **kw):
        self.raw(b"Q" + params(**kw))

    def mode(self, m):
        self.raw(b"M" + bytes([m]))

    def reset(self):
        self.raw(b"R")

    def clear(self):
        self.raw(b"K")

    def log(self):
        self.raw(b"L")

    def quiet(self, mask):
        self.raw(b"Z" + bytes([mask]))

    def step(self, row, ref, flags=F_NORMAL, vdc=VDC_V, theta_shift=0.0, omega_rpm=None,
             raw_override=None, tag="other"):
        """row: (theta_e rad, speed rpm, i_A..i_F A)."""
        theta, rpm, cur = row[0] + theta_shift, row[1], row[2]
        if omega_rpm is not None:
            rpm = omega_rpm
        self.raw(b"S" + bytes([flags]))
        self.q(ref)
        for i in cur:
            self.q(i / I_BASE)
        self.q(vdc / V_BASE)
        self.q((theta / (2.0 * math.pi)) % 1.0)
        self.q(rpm * math.pi / 30.0 * POLE_PAIRS / W_BASE)
        raws = [max(0, min(4095, int(math.floor(2048.0 + i / (40.0 / 4096.0) + 0.5)))) for i in cur]
        if raw_override is not None:
            raws = raw_override(raws)
        raw_vdc = max(0, min(4095, int(math.floor(vdc / (800.0 / 4096.0) + 0.5))))
        self.raw(struct.pack("<7h", *raws, raw_vdc))
        self.steps += 1
        self.counts[tag] = self.counts.get(tag, 0) + 1


def record(sim, work, controller, scenario, extra=()):
    d = os.path.join(work, "%s-%s" % (controller, scenario))
    cmd = [sim, "run", "--controller", controller, "--scenario", scenario, "--out", d,
           "--no-fine", "--quiet"] + list(extra)
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("gen_inputs: %s failed: %s" % (" ".join(cmd), r.stderr.strip()[-300:]))
    rows = []
    with open(os.path.join(d, "trace.csv")) as f:
        rd = csv.reader(f)
        head = next(rd)
        col = {n: i for i, n in enumerate(head)}
        idx = [col[n] for n in ("theta_e", "speed_rpm", "i_A", "i_B", "i_C", "i_D", "i_E",
                                "i_F", "Tref")]
        for r in rd:
            v = [float(r[i]) for i in idx]
            rows.append((v[0], v[1], v[2:8], v[8]))
    return rows


def tref(row):
    return row[3] / T_BASE


def speed_ref_ahead(rows, k, ahead=200):
    """Speed reference for the speed-loop runs: where the recorded speed is 20 ms later."""
    r = rows[min(len(rows) - 1, k + ahead)]
    return r[1] * math.pi / 30.0 * POLE_PAIRS / W_BASE


def build(sim, work, scale):
    s = Stream()

    def n(x):
        return max(50, int(x * scale))

    # A: DDC, flux-error reading, torque guard, torque mode, with parameter changes (OK, BUSY,
    #    refused with a reason) in mid-run; protection on every step.
    rows = record(sim, work, "ddc", "steady")
    s.init(controller=DDC, direction=FLUX_ERROR, guard=True)
    s.mode(TORQUE)
    s.reset()
    na = min(len(rows), n(5000))
    for k in range(na):
        if k == na * 3 // 10:
            s.request(controller=DDC, direction=FLUX_ERROR, guard=False, lam=50.0)  # OK
            s.request(controller=DDC, direction=XY_TABLE, guard=True)  # BUSY: not taken yet
        if k == na * 3 // 10 + 1:
            s.request(levels=1)  # refused: duty levels
            s.request(lam=3000.0)  # refused: flux weight
        if k == na * 7 // 10:
            s.request(controller=DDC, direction=XY_TABLE, guard=True, flux_mode=CONSTANT,
                      flux_wb=0.3, tlim=8.0)
        r = rows[k]
        s.step(r[:3], tref(r), tag="ddc")

    # B: DDC, x-y table reading, paper DDC (no guard), speed loop; mid-run the reading and the
    #    gains change.
    rows = record(sim, work, "ddc", "load-step", ["--ddc-direction", "xy-table", "--paper-ddc"])
    s.init(controller=DDC, direction=XY_TABLE, guard=False, fewest=False, tie=False)
    s.mode(SPEED)
    s.reset()
    nb = min(len(rows), n(4500))
    for k in range(nb):
        if k == nb // 2:
            s.request(controller=DDC, direction=FLUX_ERROR, guard=True, kp=2.0, ki=80.0,
                      levels=5, tlim=9.0, mid=True)
        r = rows[k]
        s.step(r[:3], speed_ref_ahead(rows, k), tag="ddc")

    # C: MPTC-49, torque mode; then speed mode.
    rows = record(sim, work, "mptc49", "accel", ["--no-protect"])
    s.init(controller=MPTC49, lam=100.0)
    s.mode(TORQUE)
    s.reset()
    nc = min(len(rows), n(2500))
    for k in range(nc):
        if k == nc // 2:
            s.mode(SPEED)
        r = rows[k]
        s.step(r[:3], tref(r) if k < nc // 2 else speed_ref_ahead(rows, k), tag="mptc49")

    # D: MPTC-13, speed loop over a reversal; mid-run a switch to DDC and back.
    rows = record(sim, work, "mptc13", "reversal", ["--no-protect"])
    s.init(controller=MPTC13, lam=100.0, per_set=False)  # u00 or u77 only
    s.mode(SPEED)
    s.reset()
    nd = min(len(rows), n(5000))
    for k in range(nd):
        if k == nd * 4 // 10:
            s.request(controller=DDC, direction=FLUX_ERROR, guard=True)
        if k == nd * 6 // 10:
            s.request(controller=MPTC13, lam=80.0, tlim=6.5, mid=True, fewest=False)
        r = rows[k]
        tag = "ddc" if nd * 4 // 10 < k <= nd * 6 // 10 else "mptc13"
        s.step(r[:3], speed_ref_ahead(rows, k), tag=tag)

    # G: VV-MPTC (virtual vectors), torque mode over a load step, then speed mode; mid-run a
    #    switch to MPTC-13 and back (the virtual vector in force enters the other's prediction).
    rows = record(sim, work, "vvmptc", "load-step")
    s.init(controller=VVMPTC, lam=100.0)
    s.mode(TORQUE)
    s.reset()
    ng = min(len(rows), n(3000))
    for k in range(ng):
        if k == ng // 2:
            s.mode(SPEED)
        if k == ng * 3 // 5:
            s.request(controller=MPTC13, lam=100.0)
        if k == ng * 7 // 10:
            s.request(controller=VVMPTC, lam=60.0)
        r = rows[k]
        tag = "mptc13" if ng * 3 // 5 < k <= ng * 7 // 10 else "vvmptc"
        s.step(r[:3], tref(r) if k < ng // 2 else speed_ref_ahead(rows, k), tag=tag)

    # E: protection. An unusable set first (commands all-off), then a valid one; then faults
    #    injected one after another on top of a recorded trace, each followed by log reads and
    #    a clear.
    rows = record(sim, work, "ddc", "steady", ["--seed", "7"])
    s.init(controller=DDC, levels=0)  # refused: ctl_step commands all-off
    s.mode(TORQUE)
    for k in range(20):
        s.step(rows[k][:3], tref(rows[k]), tag="ddc")
    s.request(controller=DDC, oc=12.0, os_rpm=1800.0, ov=700.0)
    ne = min(len(rows), n(4800))
    seg = max(1, ne // 12)  # the open-phase window is 400 periods: seg = 400 at scale 1

    def stuck(raws):
        return [2100] + raws[1:]

    def rail(raws):
        return raws[:2] + [4095] + raws[3:]

    for k in range(ne):
        theta, rpm, cur = rows[k][:3]
        cur = list(cur)
        phase, j = k // seg, k % seg
        kw = {}
        if phase == 0 and j == seg // 2:
            cur[0] = 16.0  # over-current spike
        elif phase == 1 and j < 8:
            kw["vdc"] = 760.0  # over-voltage (3 periods)
        elif phase == 2 and j < 5:
            kw["flags"] = F_NORMAL & ~F_ENC_OK  # encoder unhealthy
        elif phase == 3 and j < 70:
            kw["raw_override"] = stuck  # ADC word frozen while current flows
        elif phase == 4 and j < 4:
            kw["raw_override"] = rail
        elif phase == 5 and j < 2:
            kw["flags"] = F_NORMAL | F_OVERRUN | F_HW_TRIP
        elif phase == 6 and j < 10:
            kw["omega_rpm"] = 2500.0  # over-speed
        elif phase == 7 and j >= 5:
            kw["theta_shift"] = math.pi / 2.0  # encoder jump of a quarter turn
        elif phase == 8 and j < 15:
            kw["vdc"] = 300.0  # under-voltage while running
        elif phase == 9:
            kw["flags"] = F_PROTECT | F_ENC_OK | F_CALIBRATED  # stopped
        elif phase == 10:
            cur[1] *= 0.3  # phase B sensor gain drop: the A-B-C set no longer sums to zero
        elif phase >= 11:
            cur[2] = 0.0  # phase C open
        s.step((theta, rpm, cur), tref(rows[k]), tag="ddc", **kw)
        if j == seg - 1 or k == ne - 1:
            s.log()
            s.clear()
            s.log()
    build_open_phase(s, sim, work, n)
    build_foc(s, sim, work, n)
    s.raw(b"E")
    return s


def build_open_phase(s, sim, work, n):
    """F: open-phase operation. A ride-through run's five-leg periods (phase C open) through
    the post-fault step: DDC with minimum loss, then maximum torque, MPTC-13, MPTC-49, a refused
    open phase, and back to the healthy set, whose open-phase check then finds phase C."""
    rows = record(sim, work, "ddc", "fault-open-phase", ["--ride-through", "--load", "3.5"])
    rows = rows[3400:]  # five-leg operation: from 0.34 s (the isolation is at 0.32 s)
    s.init(controller=DDC, open_phase=2)
    s.mode(TORQUE)
    s.reset()
    s.quiet(0x04)
    nf = min(len(rows), n(3000))
    for k in range(nf):
        if k == nf // 4:
            s.request(controller=DDC, open_phase=2, strategy=1)
            s.quiet(0x14)
        if k == nf // 2:
            s.request(controller=MPTC13, open_phase=2)
            s.quiet(0x04)
        if k == nf // 2 + 1:
            s.request(open_phase=6)  # refused: no such phase
        if k == nf * 5 // 8:
            s.request(controller=MPTC49, open_phase=2, strategy=1)
        if k == nf * 11 // 16:
            s.request(controller=VVMPTC, open_phase=2)  # falls back to post-fault MPTC-13
        if k == nf * 3 // 4:
            s.request(controller=DDC)
            s.quiet(0)
        r = rows[k]
        s.step(r[:3], tref(r), tag="open-phase")
    s.log()


def build_foc(s, sim, work, n):
    """G: FOC-VSD over a load step, torque mode then speed mode; mid-run a switch to DDC and back
    (the FOC state is reset on the change), then a constant-flux set (i_d = 0)."""
    rows = record(sim, work, "foc", "load-step")
    s.init(controller=FOC)
    s.mode(TORQUE)
    s.reset()
    ng = min(len(rows), n(3000))
    for k in range(ng):
        if k == ng // 3:
            s.mode(SPEED)
        if k == ng // 2:
            s.request(controller=DDC)
        if k == ng * 6 // 10:
            s.request(controller=FOC, flux_mode=CONSTANT, flux_wb=0.25)
        r = rows[k]
        tag = "ddc" if ng // 2 < k <= ng * 6 // 10 else "foc"
        s.step(r[:3], tref(r) if k < ng // 3 else speed_ref_ahead(rows, k), tag=tag)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--out-fixed", required=True)
    ap.add_argument("--out-float", required=True)
    ap.add_argument("--scale", type=float, default=1.0)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    s = build(a.sim, a.work, a.scale)
    with open(a.out_fixed, "wb") as f:
        f.write(s.fixed)
    with open(a.out_float, "wb") as f:
        f.write(s.float)
    print("inputs: %d steps (%s), %d bytes per stream" %
          (s.steps, ", ".join("%s %d" % kv for kv in sorted(s.counts.items())), len(s.fixed)))


if __name__ == "__main__":
    main()
