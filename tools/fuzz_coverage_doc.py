#!/usr/bin/env python3
"""Branch coverage of the fuzz corpora, per file and function (tools/fuzz_coverage.sh).

usage: fuzz_coverage_doc.py [(--write-doc | --check-doc) DOC] [--root DIR] COVERAGE_JSON

COVERAGE_JSON is `llvm-cov export -format=text` of the replayed corpora. Branches are as
llvm-cov counts them: each outcome (true, false) of a condition is one branch, covered when
it was taken at least once. The table goes between <!-- fuzz-coverage --> and
<!-- /fuzz-coverage --> of DOC: --write-doc rewrites that block, --check-doc fails when it
differs (the replay is deterministic, so the figures are exact) or when a listed unit is
below its floor. Without a mode the table is printed and the floors are checked.
"""
import argparse
import json
import os
import sys

BEGIN = "<!-- fuzz-coverage -->"
END = "<!-- /fuzz-coverage -->"
FLOOR = 70.0

# (what, file, function or None, floor %): the units issue 24 asks the fuzzers to reach;
# the host tool's reply parsing is listed without a floor.
UNITS = [
    ("capture", "firmware/app/capture/capture.c", None, FLOOR),
    ("capture", "firmware/app/drive/drive_capture.c", None, FLOOR),
    ("converter alive", "control/src/ctl_protect.c", "ctl_protect_converter_alive", FLOOR),
    ("phase verification", "firmware/app/drive/drive_commission.c", "drive_phase_verify_period",
     FLOOR),
    ("commissioning", "firmware/app/drive/drive_commission.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/commission.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_ctx.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_excite.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_stats.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_phase.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_encoder.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_resistance.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_inductance.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_flux.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_mech.c", None, FLOOR),
    ("commissioning", "firmware/app/commission/ident_xy_harmonics.c", None, FLOOR),
    ("host tool replies", "firmware/tools/sixphase_link.c", "print_reply", None),
    ("host tool replies", "firmware/tools/sixphase_link.c", "print_profile_row", None),
    ("host tool replies", "firmware/tools/sixphase_link.c", "print_fault_record", None),
    ("host tool replies", "firmware/tools/link_capture.c", "cap_arm_reply", None),
    ("host tool replies", "firmware/tools/link_capture.c", "cap_read_reply", None),
    ("host tool replies", "firmware/tools/link_identify.c", "identify_status_reply", None),
    ("host tool replies", "firmware/tools/link_identify.c", "identify_result_reply", None),
    ("host tool replies", "firmware/tools/link_identify.c", "identify_apply_reply", None),
    ("host tool replies", "firmware/tools/link_open_phase.c", "link_open_phase_print", None),
    ("host tool replies", "firmware/tools/link_torque_limited.c", "link_torque_limited_print",
     None),
]


def fail(msg):
    sys.stderr.write("fuzz_coverage_doc: %s\n" % msg)
    sys.exit(1)


def relative(path, root):
    return os.path.relpath(os.path.realpath(path), os.path.realpath(root))


def function_branches(functions, root, path, name):
    """(covered, total) of one function, its instances in several binaries merged."""
    seen = {}
    found = False
    for f in functions:
        short = f["name"].split(":")[-1]
        if short != name or not any(relative(p, root) == path for p in f["filenames"]):
            continue
        found = True
        for b in f["branches"]:
            key = tuple(b[0:4])
            old = seen.get(key, (0, 0))
            seen[key] = (max(old[0], b[4]), max(old[1], b[5]))
    if not found:
        fail("%s: function %s not in the coverage data" % (path, name))
    covered = sum((t > 0) + (e > 0) for t, e in seen.values())
    return covered, 2 * len(seen)  # a function without a condition: 0 of 0


def measure(data, root):
    files = {}
    for f in data["data"][0]["files"]:
        files[relative(f["filename"], root)] = f["summary"]["branches"]
    rows = []
    for what, path, func, floor in UNITS:
        if func:
            covered, total = function_branches(data["data"][0]["functions"], root, path, func)
        elif path in files:
            covered, total = files[path]["covered"], files[path]["count"]
        else:
            fail("%s not in the coverage data" % path)
        rows.append((what, path, func, covered, total, floor))
    return rows


def table(rows):
    lines = [
        BEGIN,
        "| what | file (function) | branches covered | % | floor |",
        "|---|---|---|---|---|",
    ]
    for what, path, func, covered, total, floor in rows:
        unit = "`%s` (`%s`)" % (path, func) if func else "`%s`" % path
        pct = 100.0 * covered / total if total else 0.0
        lines.append("| %s | %s | %d / %d | %.1f | %s |" % (
            what, unit, covered, total, pct, "%d %%" % floor if floor else "-"))
    lines.append(END)
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--write-doc", metavar="DOC")
    mode.add_argument("--check-doc", metavar="DOC")
    ap.add_argument("--root", default=".")
    ap.add_argument("coverage")
    a = ap.parse_args()
    try:
        with open(a.coverage) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: %s" % (a.coverage, e))
    rows = measure(data, a.root)
    block = table(rows)
    print(block)
    low = [r for r in rows if r[5] and 100.0 * r[3] / max(r[4], 1) < r[5]]
    doc = a.write_doc or a.check_doc
    if doc:
        with open(doc) as f:
            text = f.read()
        start, end = text.find(BEGIN), text.find(END)
        if start < 0 or end < start:
            fail("%s has no %s ... %s block" % (doc, BEGIN, END))
        new = text[:start] + block + text[end + len(END):]
        if a.write_doc:
            with open(doc, "w") as f:
                f.write(new)
        elif new != text:
            fail("%s: the fuzz coverage block differs from the replay (tools/fuzz_coverage.sh "
                 "--write-doc rewrites it)" % doc)
    for what, path, func, covered, total, floor in low:
        sys.stderr.write("fuzz_coverage_doc: %s%s: %d of %d branches, below %d %%\n" % (
            path, " (%s)" % func if func else "", covered, total, floor))
    if low:
        sys.exit(1)


if __name__ == "__main__":
    main()
