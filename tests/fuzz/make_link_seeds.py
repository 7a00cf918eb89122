#!/usr/bin/env python3
"""Writes the seeds of fuzz_link_replies (tests/fuzz/corpus_link_replies): one well-formed
reply per parser, as a drive of protocol 8 sends them, plus short and refused ones.
Input format (fuzz_link_replies.c): parser, command, argument, payload.

usage: make_link_seeds.py [DIR]   (default: corpus_link_replies next to this script)
"""
import os
import struct
import sys

OK, REFUSED = 0, 4
STATUS, PING, PROFILE, FAULT_RECORD = 0x02, 0x01, 0x03, 0x04
CAPTURE_ARM, CAPTURE_READ = 0x20, 0x22
COMM_STATUS, COMM_RESULT, COMM_APPLY, OPEN_PHASE = 0x41, 0x42, 0x43, 0x50
TORQUE_LIMITED = 0x19


def seed(parser, cmd, arg, payload):
    return bytes([parser, cmd, arg]) + payload


STATUS_BLOCK = (bytes([3, 0, 0]) + struct.pack("<iiii", 15000, 15000, 1200, 1500)
                + struct.pack("<I", 100) + bytes([0x01]) + struct.pack("<IIH", 12345, 800, 0)
                + struct.pack("<HH", 0, 0) + bytes([0]) + struct.pack("<H", 0)
                + struct.pack("<HH", 120, 512))
SEEDS = {
    "status": seed(0, STATUS, 0, bytes([OK]) + STATUS_BLOCK[:45]),
    "status-v1": seed(0, STATUS, 0, bytes([OK]) + STATUS_BLOCK[:30]),
    "ping": seed(0, PING, 0, bytes([OK, 8])),
    "refused": seed(0, 0x12, 0, bytes([REFUSED])),
    "profile": seed(1, PROFILE, 1, bytes([OK, 7]) + bytes(range(1, 35))),
    "profile-bad-stage": seed(1, PROFILE, 0, bytes([OK, 9]) + bytes(34)),
    "fault-record": seed(2, FAULT_RECORD, 0, bytes([OK, 1]) + struct.pack("<IH", 4711, 0x0400)
                         + bytes(range(36))),
    "fault-record-empty": seed(2, FAULT_RECORD, 0, bytes([OK, 0])),
    "capture-arm": seed(3, CAPTURE_ARM, 0, bytes([OK])),
    "capture-arm-busy": seed(3, CAPTURE_ARM, 0, bytes([REFUSED])),
    "capture-read": seed(4, CAPTURE_READ, 3, bytes([OK, 20]) + bytes(range(40))),
    "capture-read-end": seed(4, CAPTURE_READ, 255, bytes([OK, 20]) + bytes(range(40))),
    "capture-read-long": seed(4, CAPTURE_READ, 0, bytes([OK, 21]) + bytes(42)),
    "comm-status": seed(5, COMM_STATUS, 0, bytes([OK, 2, 0, 5, 100]) + bytes(7)),
    "comm-result-r": seed(6, COMM_RESULT, 3, bytes([OK]) + struct.pack("<iii", 450000, 900, 0)
                          + bytes([1, 0, 0])),
    "comm-result-offset": seed(6, COMM_RESULT, 2, bytes([OK]) + struct.pack("<iii", -90000, 500, 3)
                               + bytes([1, 0, 0])),
    "comm-result-counts": seed(6, COMM_RESULT, 1, bytes([OK]) + struct.pack("<iii", 3333, 0, 3)
                               + bytes([1, 0, 0])),
    "comm-apply": seed(7, COMM_APPLY, 0, bytes([OK, 0x3E, 0])),
    "open-phase": seed(8, OPEN_PHASE, 0, bytes([OK]) + bytes([2, 1, 0, 3]) + bytes(9)),
    "torque-limited": seed(0, TORQUE_LIMITED, 0, bytes([OK, 1]) + struct.pack("<H", 200)
                           + bytes([1])),
    "torque-limited-short": seed(0, TORQUE_LIMITED, 0, bytes([OK, 0]) + struct.pack("<H", 500)),
    "torque-limited-unknown-action": seed(0, TORQUE_LIMITED, 0, bytes([OK, 7])
                                          + struct.pack("<H", 500) + bytes([0])),
}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "corpus_link_replies")
    os.makedirs(out, exist_ok=True)
    for name, data in SEEDS.items():
        with open(os.path.join(out, "seed-" + name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
