#!/usr/bin/env python3
"""Numbers in hand-written docs that are copies of what a generator or the code says (issue 26):
each is registered in tools/doc_claims.txt with where it comes from, and this check fails when the
doc's copy and its source disagree (a stale number) or the source no longer says it.

  tools/doc_claims.py [--registry FILE] [--root DIR]

Registry lines (# comments, blank lines ignored), fields separated by " || ":
  doc || text with a placeholder per number || source file || regex || regex ...
one regex per placeholder, in order, each with group 1 the number. A placeholder is {} (the
number as the source writes it) or {:.Nf} (rounded to N decimals, halves away from zero, as a
reader rounds). The text with the source's numbers put in must occur in the doc verbatim. Exit 0
when every claim holds, 1 (one line per failed claim) otherwise, 2 on a malformed registry.
"""
import argparse
import decimal
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


PLACEHOLDER = re.compile(r"\{(:\.([0-9])f)?\}")


def load(path):
    claims = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            parts = [p.strip() for p in line.split(" || ")]
            if len(parts) < 4 or len(PLACEHOLDER.findall(parts[1])) != len(parts) - 3:
                raise ValueError("%s:%d: want 'doc || text with n placeholders || source || "
                                 "n regexes'" % (path, n))
            for r in parts[3:]:
                re.compile(r)
            claims.append((n, parts[0], parts[1], parts[2], parts[3:]))
    return claims


def formatted(value, digits):
    """The source's number as the placeholder asks: as written, or rounded half up."""
    if digits is None:
        return value
    q = decimal.Decimal(1).scaleb(-int(digits))
    return str(decimal.Decimal(value).quantize(q, rounding=decimal.ROUND_HALF_UP))


def fill(text, values):
    """text with its placeholders replaced by values, and a pattern matching any number there."""
    out, pattern, pos = [], [], 0
    for m, v in zip(PLACEHOLDER.finditer(text), values):
        out.append(text[pos:m.start()] + formatted(v, m.group(2)))
        pattern.append(re.escape(text[pos:m.start()]) + r"(\S+?)")
        pos = m.end()
    out.append(text[pos:])
    pattern.append(re.escape(text[pos:]))
    return "".join(out), "".join(pattern)


def read(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.read()


def check(root, claims):
    """The failures, one line each."""
    failures = []
    for n, doc, text, source, regexes in claims:
        try:
            src = read(root, source)
            body = read(root, doc)
        except OSError as e:
            failures.append("claim %d: %s" % (n, e))
            continue
        values = []
        for r in regexes:
            m = re.search(r, src, re.MULTILINE)
            if not m:
                failures.append("claim %d: %s no longer matches /%s/ (the claim in %s needs a "
                                "new source)" % (n, source, r, doc))
                break
            values.append(m.group(1))
        if len(values) != len(regexes):
            continue
        expected, pattern = fill(text, values)
        if expected not in body:
            found = re.search(pattern, body)
            was = (" (it says '%s')" % found.group(0)) if found else ""
            failures.append("claim %d: %s should say '%s' as %s does%s" %
                            (n, doc, expected, source, was))
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--registry", default=os.path.join(HERE, "doc_claims.txt"))
    ap.add_argument("--root", default=ROOT)
    a = ap.parse_args()
    try:
        claims = load(a.registry)
    except (OSError, ValueError, re.error) as e:
        print("doc_claims: %s" % e, file=sys.stderr)
        return 2
    failures = check(a.root, claims)
    for f in failures:
        print("doc_claims: %s" % f, file=sys.stderr)
    print("doc_claims: %d claims, %d stale" % (len(claims), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
