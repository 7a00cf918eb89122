#!/usr/bin/env python3
"""Fails when a C function is longer than the limit (lines from the opening to the closing
brace at column 0, the project's clang-format layout). usage: check_function_length.py
--max N FILE_OR_DIR..."""
import argparse
import pathlib
import re
import sys



def functions(path):
    lines = path.read_text().splitlines()
    i = 0
    while i < len(lines):
        if lines[i] == "{" and i > 0:
            # the signature ends on the line before the brace; find where it starts
            j = i - 1
            while j > 0 and not re.match(r"^[A-Za-z_]", lines[j]):
                j -= 1
            start = i
            k = i + 1
            while k < len(lines) and lines[k] != "}":
                k += 1
            name = re.search(r"([A-Za-z_][A-Za-z_0-9]*)\s*\(", lines[j])
            yield (name.group(1) if name else lines[j].strip()), j + 1, k - start + 1
            i = k
        i += 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max", type=int, required=True)
    ap.add_argument("paths", nargs="+")
    args = ap.parse_args()
    files = []
    for p in map(pathlib.Path, args.paths):
        if not p.exists():
            sys.exit(f"check_function_length: no such file or directory: {p}")
        files += sorted(p.rglob("*.c")) if p.is_dir() else [p]
    long_ones = [(f, name, line, n) for f in files for name, line, n in functions(f) if n > args.max]
    for f, name, line, n in long_ones:
        print(f"{f}:{line}: {name} is {n} lines (limit {args.max})")
    if long_ones:
        sys.exit(1)
    print(f"check_function_length: {len(files)} files, every function at most {args.max} lines")


if __name__ == "__main__":
    main()
