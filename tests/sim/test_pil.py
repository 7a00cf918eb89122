#!/usr/bin/env python3
"""Processor in the loop end to end on the emulated target (QEMU's MPS2 AN386, Cortex-M4F):
the fixed image bit-identical with the host's build at every period over 2,000 and more
closed-loop periods of steady operation, a load step and an open phase ridden through; the float
image within its tolerance; the cycle report (metrics.json's "pil", pil.csv a row a period,
pil.png) written; at least 200 periods a second through the link; the same through
`serial:PATH` (QEMU started here, its pseudo-terminal given as a serial port); and the refusals:
a bad target, serve or sweep with --pil, an image of the other arithmetic, a line nobody
answers.
usage: test_pil.py --sim SIXPHASE_SIM"""
import argparse
import csv
import json
import os
import pty
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

SIM = None
MIN_STEPS = 2000
MIN_STEPS_PER_S = 200.0


def run(args, out=None, env=None, timeout=600):
    cmd = [SIM, "run", "--controller", "ddc"] + args + (["--out", out] if out else [])
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          timeout=timeout, env=env)


class PilTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="sixphase-pil-")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def closed_loop(self, args, arith="fixed", plot=False):
        out = os.path.join(self.dir, "run")
        p = run(args + ["--arith", arith, "--pil", "qemu"] + (["--plot"] if plot else []), out)
        self.assertEqual(p.returncode, 0, p.stderr)
        metrics = json.loads(p.stdout)
        pil = metrics["pil"]
        self.assertGreaterEqual(pil["steps"], MIN_STEPS)
        self.assertGreaterEqual(pil["steps_per_s"], MIN_STEPS_PER_S, pil)
        with open(os.path.join(out, "pil.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), pil["steps"])
        running = [r for r in rows if r["state"] == "3"]
        self.assertGreater(len(running), MIN_STEPS // 2)
        for r in running:  # every period in RUN counted, its stages within the whole ISR
            stages = sum(int(r[k]) for k in ("adc", "transforms", "predict", "table", "search",
                                             "pwm"))
            self.assertGreater(int(r["cycles"]), 0)
            self.assertLessEqual(stages, int(r["cycles"]))
        self.assertGreater(pil["cycles_in_run"]["mean_instructions"], 0.0)
        self.assertEqual(sum(pil["histogram"]["counts"]), pil["steps"])
        if plot:
            self.assertTrue(os.path.getsize(os.path.join(out, "pil.png")) > 10000)
        return metrics, pil

    def test_steady_fixed_bit_identical_with_report(self):
        _, pil = self.closed_loop(["--scenario", "steady", "--duration", "0.25"], plot=True)
        self.assertTrue(pil["identical"], pil["first_difference"])
        self.assertEqual(pil["largest_duty_difference_counts"], 0)

    def test_load_step_fixed_bit_identical(self):
        m, pil = self.closed_loop(["--scenario", "load-step", "--duration", "0.25"])
        self.assertTrue(pil["identical"], pil["first_difference"])
        self.assertGreater(m["torque_mean_nm"], 1.0)

    def test_open_phase_ridden_through_bit_identical(self):
        m, pil = self.closed_loop(["--scenario", "fault-open-phase", "--ride-through",
                                   "--open-phase", "C", "--fault-time", "0.08",
                                   "--duration", "0.25"])
        self.assertTrue(pil["identical"], pil["first_difference"])
        self.assertEqual(m["open_phase"]["isolated_leg"], 2)
        self.assertEqual(m["fault_name"], "NONE")

    def test_float_within_tolerance(self):
        _, pil = self.closed_loop(["--scenario", "steady", "--duration", "0.22"], arith="float")
        self.assertEqual(pil["differing_steps"], 0, pil["first_difference"])

    def test_serial_port(self):
        """The board's path: the target named by its serial line (QEMU started here)."""
        image = os.path.join(os.environ.get("SIXPHASE_PIL_IMAGE_DIR", IMAGE_DIR),
                             "pil-mps2-fixed.elf")
        q = subprocess.Popen(["qemu-system-arm", "-machine", "mps2-an386", "-nographic",
                              "-monitor", "none", "-serial", "pty", "-icount", "shift=6",
                              "-kernel", image], stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True)
        try:
            line = q.stdout.readline()
            m = re.search(r"(/dev/pts/\d+)", line)
            self.assertIsNotNone(m, line)
            p = run(["--scenario", "steady", "--duration", "0.05", "--pil",
                     "serial:%s@921600" % m.group(1)])
            self.assertEqual(p.returncode, 0, p.stderr)
            pil = json.loads(p.stdout)["pil"]
            self.assertTrue(pil["identical"])
            self.assertFalse(pil["emulated"])  # as the host sees a board: us, not instructions
            self.assertIn("mean_us", pil["cycles"])
        finally:
            q.kill()
            q.wait()

    def test_refusals(self):
        cases = [
            (["--scenario", "steady", "--pil", "bogus"], 2, "--pil takes qemu or serial"),
            (["--scenario", "steady", "--pil", "serial:"], 2, "the path is missing"),
            (["--scenario", "steady", "--pil", "serial:/dev/null@123"], 2, "BAUD must be"),
            (["--scenario", "steady", "--pil", "serial:/nonexistent"], 1, "cannot open"),
        ]
        for args, rc, text in cases:
            p = run(args)
            self.assertEqual(p.returncode, rc, (args, p.stderr))
            self.assertIn(text, p.stderr)
            self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
        p = subprocess.run([SIM, "serve", "--pil", "qemu"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=30)
        self.assertEqual(p.returncode, 2)
        self.assertIn("serve has no --pil", p.stderr)
        p = subprocess.run([SIM, "sweep", "--out", os.path.join(self.dir, "sw"), "--controller",
                            "ddc", "--lambda", "10,20", "--pil", "qemu"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=30)
        self.assertEqual(p.returncode, 2)
        self.assertIn("--pil is for one run", p.stderr)

    def test_image_of_the_other_arithmetic_refused(self):
        fake = os.path.join(self.dir, "images")
        os.makedirs(fake)
        shutil.copy(os.path.join(IMAGE_DIR, "pil-mps2-float.elf"),
                    os.path.join(fake, "pil-mps2-fixed.elf"))
        env = dict(os.environ, SIXPHASE_PIL_IMAGE_DIR=fake)
        p = run(["--scenario", "steady", "--duration", "0.05", "--pil", "qemu"], env=env)
        self.assertEqual(p.returncode, 1)
        self.assertIn("the target's image is the float build", p.stderr)

    def test_documented_frame_sizes(self):
        """docs/profiling.md's bytes a period: the protocol's own sizes."""
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
        with open(os.path.join(root, "firmware", "link", "sxlink_pil.h")) as f:
            header = f.read()
        with open(os.path.join(root, "firmware", "link", "sxlink.h")) as f:
            link = f.read()
        with open(os.path.join(root, "docs", "profiling.md")) as f:
            doc = " ".join(f.read().split())

        def const(text, name):
            return int(re.search(r"#define %s (\d+)u" % name, text).group(1))
        overhead = 3 + const(link, "SXL_CRC_BYTES")  # start byte, length, command; the CRC
        request = const(header, "SXL_PIL_IN_BYTES") + overhead + 1  # the background's call
        reply = const(header, "SXL_PIL_OUT_BYTES") + overhead
        self.assertIn("(at least %d:" % request, doc)
        self.assertIn("SXL_PIL_OUT_BYTES + %d (%d)" % (overhead, reply), doc)
        self.assertIn("SXL_PIL_IN_BYTES + %d bytes" % overhead, doc)

    def test_silent_line_times_out(self):
        master, slave = pty.openpty()
        try:
            t0 = time.monotonic()
            p = run(["--scenario", "steady", "--duration", "0.05", "--pil",
                     "serial:%s" % os.ttyname(slave)])
            self.assertEqual(p.returncode, 1)
            self.assertIn("no answer to PIL_HELLO", p.stderr)
            self.assertLess(time.monotonic() - t0, 20.0)
        finally:
            os.close(master)
            os.close(slave)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--images", required=True, help="the directory of the PIL images")
    a, rest = ap.parse_known_args()
    SIM = a.sim
    IMAGE_DIR = a.images
    for tool in ("qemu-system-arm",):
        if shutil.which(tool) is None:
            sys.exit("test_pil: %s not found (tools/install-deps.sh installs it)" % tool)
    for arith in ("fixed", "float"):
        if not os.path.exists(os.path.join(IMAGE_DIR, "pil-mps2-%s.elf" % arith)):
            sys.exit("test_pil: the PIL image %s is missing (arm-none-eabi-gcc at configure time)"
                     % arith)
    unittest.main(argv=[sys.argv[0]] + rest)
