#!/usr/bin/env python3
"""Writes the structured seeds of fuzz_drive (seed-plant-*, seed-capture-*): inputs in
fuzz_drive's format that reach the commissioning steps, capture, the converter-alive check and
the phase verification, which random bytes rarely do. The seeds that run whole commissioning
sequences or more than fuzz_drive's short budget of plant periods (LONG_START) go to
corpus_drive_long: replayed by every build and by tools/fuzz_coverage.sh, but not mutated by
CI's fuzz run (their mutants would be as slow: a plant period costs about a hundred plain
ones under the sanitizers); the others to corpus_drive.

usage: make_drive_seeds.py [DIR]   (default: the folder of this script; writes DIR/corpus_drive
                                    and DIR/corpus_drive_long)
"""
import os
import struct
import sys

CALIBRATED = b"\x01"  # first byte odd: start from the calibrated snapshot (READY)
LONG_START = b"\x03"  # and bit 1: the long plant budget (the whole commissioning sequence)
# serial_frame picks (fuzz_drive.c): commands[pick % 14] below 240, commissioning 240..243,
# the torque-limited set and read 244..247
PING, STATUS, PROFILE, FAULT_RECORD, SET_SPEED, SET_TORQUE, RUN, STOP, CLEAR = range(9)
COMM_START, COMM_STATUS, COMM_RESULT, COMM_APPLY = 240, 241, 242, 243
FRAME_TAG, BACKGROUND_TAG, PLANT_TAG, CAPTURE_TAG = 1, 5, 248, 250


def frame(pick, payload=b""):
    return bytes([FRAME_TAG, pick, len(payload)]) + payload


def plant(blocks, phase_open=None, frozen=False, homed=True, load=False):
    """blocks x 256 periods on the plant (tags of at most 256 periods); the encoder homed
    unless the input's first plant tag says otherwise (commissioning finds the index)."""
    out = b""
    flags = (7 if phase_open is None else phase_open) | (8 if frozen else 0) | (16 if homed else 0) \
        | (32 if load else 0)
    return bytes([PLANT_TAG, flags, 7]) * blocks


def commission(mask, permille=400):
    return frame(COMM_START, struct.pack("<BH", mask, permille))


def results():
    out = frame(COMM_STATUS) + bytes([BACKGROUND_TAG, 0])
    for q in range(10):
        out += frame(COMM_RESULT, bytes([q]))
    return out + frame(COMM_APPLY) + bytes([BACKGROUND_TAG, 0])


def capture_arm(chans, signals, length_div4, decimation, trigger, trig_signal, level, pre):
    what = ((chans - 1) << 2) | (trigger << 5)
    return bytes([CAPTURE_TAG, what] + signals + [length_div4, decimation, trig_signal,
                                                   level & 0xFF, pre])


def capture_reads():
    out = bytes([CAPTURE_TAG, 1])
    for ch in range(5):
        for first in (0, 3, 40):
            out += bytes([CAPTURE_TAG, 2 | (ch << 2), first])
    return out


def raw_frame(cmd, payload):
    """Any command byte (serial_frame's picks 248 and up) with an arbitrary payload."""
    return bytes([FRAME_TAG, 248, cmd, len(payload)]) + payload


def words(phase, vdc, flags):
    """One control period's tag with given ADC words (flags: 1 posted, 4 encoder healthy,
    16 index seen)."""
    out = bytes([3, flags, 0])
    for w in phase:
        out += struct.pack(">H", w)
    return out + struct.pack(">I", vdc) + bytes(4) + bytes(2) + bytes(4)


def speed(rpm):
    return frame(SET_SPEED, struct.pack("<i", int(rpm * 10)))


ISOLATE, RESTORE = 12, 13
MID = [2048] * 6

SEEDS = {
    # the starts commissioning refuses: bad mask or current, not READY, rotor turning, a leg
    # isolated, under-voltage, an encoder error; a start whose conditions change before the
    # period; an apply while a parameter set waits
    "seed-plant-commission-refused": LONG_START + commission(0x02) + commission(0x01, 50)
    + speed(600) + frame(RUN) + plant(8, load=False) + commission(0x01) + frame(STOP)
    + plant(0, homed=True) + commission(0x01) + frame(ISOLATE, bytes([3])) + words(MID, 2765, 5)
    + commission(0x01) + frame(RESTORE) + words(MID, 2765, 5) + words(MID, 100, 5)
    + commission(0x01) + words(MID, 2765, 0x11) + commission(0x01) + words(MID, 2765, 5)
    + commission(0x01) + frame(ISOLATE, bytes([1])) + words(MID, 2765, 5) + frame(RESTORE)
    + words(MID, 2765, 5) + frame(COMM_APPLY) + bytes([2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                                          0, 0, 0]) + frame(COMM_APPLY),
    # the whole sequence, then its results read and applied
    "seed-plant-commission-all": LONG_START + commission(0x3F) + plant(1100, homed=False) + results(),
    # the mechanics' step after the phase check and the encoder (the probe, the friction points,
    # the runs): 17.5 s + 11.5 s of plant
    "seed-plant-commission-mech": LONG_START + commission(0x43) + plant(1200, homed=False)
    + results(),
    "seed-plant-commission-r": LONG_START + commission(0x07, 800) + plant(500, homed=False) + results(),
    "seed-plant-commission-ldq": LONG_START + commission(0x1B, 200) + plant(600, homed=False) + results(),
    "seed-plant-commission-stop": LONG_START + commission(0x3F) + plant(12, homed=False) + frame(STOP)
    + plant(2) + results(),
    # stopped in the psi_f step (L_d and L_q ok, psi_f without a number): APPLY refuses the mixed
    # set (docs/commissioning.md 3.1)
    "seed-plant-commission-mixed": LONG_START + commission(0x3F) + plant(940, homed=False)
    + frame(STOP) + plant(2) + results(),
    "seed-plant-commission-open": LONG_START + commission(0x3F) + plant(20, phase_open=2, homed=False)
    + results(),
    # RUN on the plant, a phase opens: OPEN_PHASE; cleared, RUN verifies the phases (open
    # still: a trip again; connected: it runs)
    "seed-plant-open-phase": LONG_START + speed(300) + frame(RUN) + plant(4, load=True)
    + plant(4, phase_open=4, load=True) + frame(CLEAR) + plant(1, phase_open=4) + frame(RUN)
    + plant(2, phase_open=4) + frame(CLEAR) + plant(1) + frame(RUN) + plant(3)
    + frame(FAULT_RECORD) + frame(FAULT_RECORD),
    # a frozen converter: ADC_STUCK; clears refused while frozen, accepted once it moves
    "seed-plant-adc-stuck": LONG_START + speed(300) + frame(RUN) + plant(4, load=True)
    + plant(1, frozen=True, load=True) + frame(CLEAR)
    + plant(1, frozen=True) + frame(CLEAR) + plant(1) + frame(CLEAR) + plant(6) + frame(CLEAR)
    + plant(1) + frame(RUN) + plant(2),
    # capture: immediate, rising, falling and fault triggers on a running drive
    "seed-capture-immediate": CALIBRATED + capture_arm(4, [0, 6, 12, 18], 32, 1, 0, 0, 0, 0)
    + speed(200) + frame(RUN) + plant(2) + capture_reads() + bytes([CAPTURE_TAG, 3]),
    "seed-capture-rising": LONG_START + capture_arm(2, [1, 7], 100, 2, 1, 0, 0, 50)
    + speed(600) + frame(RUN) + plant(8, load=True) + capture_reads(),
    "seed-capture-falling": LONG_START + capture_arm(3, [8, 10, 11], 4, 1, 2, 1, 0, 100)
    + speed(-600) + frame(RUN) + plant(8, load=True) + capture_reads() + bytes([CAPTURE_TAG, 3])
    + capture_arm(4, [13, 16, 17, 9], 30, 3, 1, 2, 0, 10) + plant(4, load=True)
    + capture_reads(),
    "seed-capture-bad-setup": CALIBRATED + raw_frame(0x20, bytes([0] + [0] * 13))
    + raw_frame(0x20, bytes([5, 0, 0, 0, 0, 8, 0, 1, 0, 0, 0, 0, 0, 0]))
    + raw_frame(0x20, bytes([1, 0, 0, 0, 0, 8, 0, 1, 0, 0, 30, 0, 0, 0]))
    + raw_frame(0x20, bytes([1, 0, 0, 0, 0, 8, 0, 1, 0, 7, 0, 0, 0, 0]))
    + raw_frame(0x20, bytes([1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0]))
    + raw_frame(0x20, bytes([1, 0, 0, 0, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0]))
    + raw_frame(0x20, bytes([1, 0, 0, 0, 0, 8, 0, 1, 0, 0, 0, 0, 0, 101]))
    + raw_frame(0x20, bytes([4, 0, 1, 2, 3, 0, 8, 1, 0, 0, 0, 0, 0, 0]))
    + raw_frame(0x21, b"") + raw_frame(0x22, bytes([9, 0, 0])),
    "seed-capture-fault": LONG_START + capture_arm(1, [19], 255, 3, 3, 0, 0, 90)
    + capture_arm(1, [3], 10, 1, 0, 0, 0, 0) + speed(300) + frame(RUN) + plant(4, load=True)
    + plant(6, phase_open=1, load=True) + capture_reads() + bytes([CAPTURE_TAG, 3])
    + capture_arm(4, [20, 21, 5, 11], 200, 0, 0, 0, 0, 0)
    + capture_arm(4, [22, 23, 16, 17], 255, 4, 1, 30, 0, 120),
}


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, data in SEEDS.items():
        sub = "corpus_drive_long" if data.startswith(LONG_START) else "corpus_drive"
        os.makedirs(os.path.join(root, sub), exist_ok=True)
        with open(os.path.join(root, sub, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
