#!/usr/bin/env python3
"""Compares the output streams of tools/avr_proxy/replay.c from the host and the AVR build.

usage: compare.py --arith {fixed,float} [--quiet] [--summary FILE.json] HOST_OUT AVR_OUT
fixed: the streams must be byte-identical; otherwise the first differing record and field.
float: the commands (vector, duty, leg duties, enable) must be identical; every other field
       that differs is reported (the largest difference of each number field).
Exit status 0 when the rule holds, 1 otherwise. --summary writes the result as JSON (steps,
records, bytes, identical, largest diagnostic difference and its field) for the benchmark
report (tools/bench/run_benchmark.py).
"""
import argparse
import json
import struct
import sys

# field kinds: u8 (also bool), u16, i16, u32, q (ctl_q bit pattern)
SIZES = {"u8": 1, "u16": 2, "i16": 2, "u32": 4, "q": 4}

CONFIG = ([(n, "q") for n in ("a_d", "b_d", "c_d", "a_q", "b_q", "e_q", "c_q", "a_xy", "c_xy",
                               "ld", "lq", "lxy", "psi_f", "ts", "omega_max")] +
          [("pole_pairs", "i16")] +
          [(n, "q") for n in ("lambda", "torque_limit", "speed_kp", "speed_ki_ts")] +
          # a FOC set: w_c, its i_d table [0..8], 0, 0 in these 12 fields (they share the place)
          [("duty_level[%d]" % i, "q") for i in range(11)] + [("ddc.tie_per_span", "q")] +
          [("omega_pu_per_rev_s", "q"), ("flux_ref.mode", "u8"), ("flux_ref.constant", "q"),
           ("flux_ref.torque_max", "q"), ("flux_ref.points_per_torque", "q")] +
          [("flux_ref.table[%d]" % i, "q") for i in range(33)] +
          [("prot.overcurrent", "q"), ("prot.overcurrent_periods", "i16"),
           ("prot.dc_overvoltage", "q"), ("prot.dc_overvoltage_periods", "i16"),
           ("prot.dc_undervoltage", "q"), ("prot.dc_undervoltage_periods", "i16"),
           ("prot.overspeed", "q"), ("prot.overspeed_periods", "i16"),
           ("prot.current_sum", "q"), ("prot.current_sum_periods", "i16"),
           ("prot.adc_rail_low", "i16"), ("prot.adc_rail_high", "i16"),
           ("prot.adc_rail_periods", "i16"), ("prot.adc_stuck_periods", "i16")] +
          [("prot." + n, "q") for n in ("stuck_min_current", "encoder_torque",
                                        "encoder_expected_turn", "encoder_jump",
                                        "torque_to_dspeed", "ts_turns", "open_phase_min_mean",
                                        "open_phase_ratio", "open_phase_fast_ratio",
                                        "open_phase_fast_min", "open_phase_fast_keep")])

STEP = ([("vector", "i16"), ("duty", "q")] + [("leg_duty[%d]" % i, "q") for i in range(6)] +
        [("enable", "u8"), ("faults", "u16"), ("latched", "u16"), ("active", "u16"),
         ("log_write", "u16"), ("flux_sector", "i16"), ("xy_sector", "i16"),
         ("candidates", "i16"), ("braking", "u8")] +
        [(n, "q") for n in ("i_d", "i_q", "i_x", "i_y", "torque_est", "flux_est",
                            "torque_ref", "flux_ref", "torque_pred", "flux_pred", "cost",
                            "speed_integ")])
COMMAND = {"vector", "duty", "enable"} | {"leg_duty[%d]" % i for i in range(6)}

LOG_RECORD = ([("ok", "u8"), ("faults", "u16"), ("period", "u32")] +
              [("i_phase[%d]" % i, "q") for i in range(6)] +
              [(n, "q") for n in ("vdc", "theta_e", "omega_e", "torque_est", "torque_ref")] +
              [("vector", "i16"), ("duty", "q")])


class Reader:
    def __init__(self, data, name):
        self.d, self.p, self.name = data, 0, name

    def get(self, kind):
        n = SIZES[kind]
        if self.p + n > len(self.d):
            raise EOFError("%s output ends at byte %d" % (self.name, self.p))
        b = self.d[self.p:self.p + n]
        self.p += n
        return b


POSTFAULT_HEAD = ([("zero_leg", "i16"), ("quiet", "u16")] +
                  [(n, "q") for n in ("c_alpha", "c_beta", "c_x", "c_y", "free_ref_alpha",
                                      "free_ref_beta")] +
                  [("peak_ratio", "u32")] +
                  [("ddc_table[%d]" % i, "i16") for i in range(12 * 2 * 2 * 2)])


def take_postfault(r, take, fields, prefix):
    """The open-phase part of a configuration (replay.c emit_postfault): open leg, and when
    there is one its geometry, DDC table and the two MPTC sets with their counts."""
    take([("open_leg", "i16")], prefix)
    if struct.unpack("<h", fields[-1][2])[0] < 0:
        return
    take(POSTFAULT_HEAD, prefix)
    for name in ("mptc_all", "mptc_large"):
        take([(name + "_count", "i16")], prefix)
        count = struct.unpack("<h", fields[-1][2])[0]
        take([("%s[%d]" % (name, i), "i16") for i in range(max(0, min(count, 32)))], prefix)


def records(r):
    """Yields (tag, [(field, kind, bytes)]) per record."""
    while r.p < len(r.d):
        tag = chr(r.get("u8")[0])
        fields = []

        def take(layout, prefix=""):
            for name, kind in layout:
                fields.append((prefix + name, kind, r.get(kind)))

        if tag == "S":
            take(STEP)
        elif tag == "N":
            take([("ok", "u8"), ("last_error", "u8")])
            if fields[0][2][0]:
                take(CONFIG, "config.")
                take_postfault(r, take, fields, "postfault.")
        elif tag == "Q":
            take([("result", "u8"), ("rejected", "u16"), ("last_error", "u8"), ("pending", "u8")])
            take(CONFIG, "config.")
            if fields[0][2][0] == 0:
                take_postfault(r, take, fields, "postfault.")
        elif tag == "Z":
            take([("inv_judged", "q")])
        elif tag == "K":
            take([("ok", "u8"), ("latched", "u16"), ("active", "u16")])
        elif tag == "L":
            take([("n", "u8")])
            for k in range(fields[0][2][0]):
                take(LOG_RECORD, "log[%d]." % k)
            take([("dropped", "u16")])
        elif tag == "E":
            take([("steps", "u32")])
        else:
            raise ValueError("%s: unknown record tag %r at byte %d" % (r.name, tag, r.p - 1))
        yield tag, fields


def value(kind, b, arith):
    if kind == "q":
        return struct.unpack("<f", b)[0] if arith == "float" else struct.unpack("<i", b)[0] / 2.0**24
    return {"u8": lambda: b[0], "u16": lambda: struct.unpack("<H", b)[0],
            "i16": lambda: struct.unpack("<h", b)[0], "u32": lambda: struct.unpack("<I", b)[0]}[kind]()


def fmt(kind, b, arith):
    v = value(kind, b, arith)
    return ("%.9g (0x%s)" % (v, b[::-1].hex())) if kind == "q" else str(v)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--arith", choices=("fixed", "float"), required=True)
    ap.add_argument("--quiet", action="store_true", help="no coverage line")
    ap.add_argument("--summary", help="write the result as JSON")
    ap.add_argument("host")
    ap.add_argument("avr")
    a = ap.parse_args()
    host = open(a.host, "rb").read()
    avr = open(a.avr, "rb").read()
    label = "compare[%s]" % a.arith
    hr, ar = Reader(host, "host"), Reader(avr, "avr")
    steps = 0
    nrec = 0
    failed = False
    first = None
    diffs = {}  # field -> [count, max abs diff]
    cov = {"results": {}, "faults": 0, "off": 0, "braking": 0, "candidates": set(), "clears": 0,
           "log_records": 0}
    try:
        for (ht, hf), (at, af) in zip(records(hr), records(ar)):
            nrec += 1
            if ht != at:
                first = first or "record %d (after %d steps): tag %s on the host, %s on the AVR" % (
                    nrec, steps, ht, at)
                failed = True
                break
            if ht == "S":
                steps += 1
                f = {name: value(kind, b, a.arith) for name, kind, b in hf}
                cov["faults"] |= f["faults"]
                cov["off"] += 0 if f["enable"] else 1
                cov["braking"] += f["braking"]
                cov["candidates"].add(f["candidates"])
            elif ht == "Q":
                code = hf[0][2][0]
                cov["results"][code] = cov["results"].get(code, 0) + 1
            elif ht == "K":
                cov["clears"] += hf[0][2][0]
            elif ht == "L":
                cov["log_records"] += hf[0][2][0]
            for (name, kind, hb), (_, _, ab) in zip(hf, af):
                if hb == ab:
                    continue
                key = ht + ":" + (name.split(".", 1)[1] if name.startswith("log[") else name)
                where = ("step %d" % (steps - 1)) if ht == "S" else ("record %d '%s' after %d steps"
                                                                      % (nrec, ht, steps))
                msg = "%s field %s: host %s, avr %s" % (where, name, fmt(kind, hb, a.arith),
                                                        fmt(kind, ab, a.arith))
                strict = a.arith == "fixed" or (ht == "S" and name in COMMAND)
                if strict and not failed:
                    first = msg
                    failed = True
                d = diffs.setdefault(key, [0, 0.0, msg])
                d[0] += 1
                d[1] = max(d[1], abs(value(kind, hb, a.arith) - value(kind, ab, a.arith)))
            if failed and a.arith == "fixed":
                break
    except (EOFError, ValueError) as e:
        print("%s: FAIL: %s" % (label, e))
        return 1
    if len(host) != len(avr) and not failed:
        failed = True
        first = "output lengths differ: host %d bytes, avr %d bytes" % (len(host), len(avr))
    largest = max(diffs.items(), key=lambda kv: kv[1][1], default=(None, [0, 0.0, ""]))
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump({"arith": a.arith, "ok": not failed, "steps": steps, "records": nrec,
                       "bytes": len(host), "identical": host == avr,
                       "max_diag_diff": largest[1][1], "max_diag_field": largest[0]}, f)
    if failed:
        print("%s: FAIL: first difference: %s" % (label, first))
        for key, (n, m, msg) in sorted(diffs.items())[:20]:
            print("  %s: %d differences, max |diff| %.3g; first: %s" % (key, n, m, msg))
        return 1
    identical = host == avr
    if not a.quiet:
        print("%s: coverage: parameter requests by result %s (0 ok, 1 busy, 4 duty levels, "
              "5 lambda); fault bits seen 0x%04x; all-off steps %d; braking steps %d; "
              "candidates per step %s; clears accepted %d; log records read %d" % (
                  label, dict(sorted(cov["results"].items())), cov["faults"], cov["off"],
                  cov["braking"], sorted(cov["candidates"]), cov["clears"],
                  cov["log_records"]))
    print("%s: ok: %d steps, %d records, %d bytes compared, %s" % (
        label, steps, nrec, len(host), "byte-identical" if identical else "commands identical"))
    if a.arith == "float":
        if not diffs:
            print("%s: diagnostics: max difference 0 (every field identical)" % label)
        for key, (n, m, msg) in sorted(diffs.items()):
            print("%s: diagnostics %s: %d differences, max |diff| %.3g" % (label, key, n, m))
    return 0


if __name__ == "__main__":
    sys.exit(main())
