"""What the generated doc tables share: the command line (--write | --check, with --sim and
--jobs for the simulator-driven ones, --exe for those a program of the build prints), one
simulator run's metrics, one program's output, and the block between two markers of a doc,
rewritten or compared."""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parser(description, doc_name):
    """The tools' common options; add a tool's own before parse_args."""
    ap = argparse.ArgumentParser(description=description)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true", help="rewrite the table in " + doc_name)
    mode.add_argument("--check", action="store_true", help="compare with the committed table")
    ap.add_argument("--sim", default=os.environ.get(
        "SIXPHASE_SIM", os.path.join(ROOT, "build", "host", "host_sim", "sixphase-sim")))
    ap.add_argument("--jobs", type=int, default=2)
    return ap


def program_parser(description, program):
    """--write | --check and --exe, the program of the build that prints the tables."""
    ap = argparse.ArgumentParser(description=description)
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", action="store_true")
    mode.add_argument("--check", action="store_true")
    ap.add_argument("--exe", required=True, help="the %s program" % program)
    return ap


def program_output(tool, exe, program, args=()):
    """What exe prints for args, or None after a one-line error (no program, or it failed)."""
    if not os.access(exe, os.X_OK):
        print("%s: no program at %s (build the %s target)" % (tool, exe, program),
              file=sys.stderr)
        return None
    out = subprocess.run([exe] + list(args), capture_output=True, text=True, check=False)
    if out.returncode != 0:
        print("%s: %s %s failed: %s" % (tool, exe, " ".join(args), out.stderr.strip()),
              file=sys.stderr)
        return None
    return out.stdout


def run_json(sim, args):
    """The metrics (JSON) of `sixphase-sim run --no-trace` with args; RuntimeError naming the
    command and its error when the run fails."""
    cmd = [sim, "run", "--no-trace"] + list(args)
    out = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), out.stderr.strip()))
    return json.loads(out.stdout)


def usable(tool, a):
    """False (with a one-line error) when the simulator or --jobs cannot be used."""
    if not os.access(a.sim, os.X_OK):
        print("%s: no simulator at %s (build it, or --sim)" % (tool, a.sim), file=sys.stderr)
        return False
    if a.jobs < 1:
        print("%s: --jobs must be at least 1" % tool, file=sys.stderr)
        return False
    return True


def update_block(tool, doc_path, begin, end, block, a):
    """Puts block between the markers (--write) or compares it with what is there (--check);
    0, or 1 with a one-line error when the markers are missing or (--check) the doc differs."""
    with open(doc_path, encoding="utf-8") as f:
        doc = f.read()
    if begin not in doc or end not in doc:
        print("%s: %s has no markers for its table" % (tool, doc_path), file=sys.stderr)
        return 1
    start = doc.index(begin) + len(begin)
    new = doc[:start] + "\n" + block + doc[doc.index(end):]
    if a.write and new != doc:
        with open(doc_path, "w", encoding="utf-8") as f:
            f.write(new)
    if a.check and new != doc:
        print("%s: the table in %s is out of date; run tools/%s.py --write and commit the result"
              % (tool, os.path.relpath(doc_path, ROOT), tool), file=sys.stderr)
        return 1
    return 0
