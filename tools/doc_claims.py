#!/usr/bin/env python3
"""Numbers in hand-written docs that are copies of what a generator or the code says (issue 26):
each is registered in tools/doc_claims.txt with where it comes from, and this check fails when the
doc's copy and its source disagree (a stale number) or the source no longer says it.

  tools/doc_claims.py [--registry FILE] [--root DIR]

Registry lines (# comments, blank lines ignored), four fields separated by " || ":
  doc || text with {} where the number stands || source file || regex, group 1 the number
The source's number, put into the text, must occur in the doc verbatim. Exit 0 when every claim
holds, 1 (one line per failed claim) otherwise, 2 on a malformed registry.
"""
import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def load(path):
    claims = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            parts = [p.strip() for p in line.split(" || ")]
            if len(parts) != 4 or parts[1].count("{}") != 1:
                raise ValueError("%s:%d: want 'doc || text with one {} || source || regex'" %
                                 (path, n))
            re.compile(parts[3])
            claims.append((n, parts[0], parts[1], parts[2], parts[3]))
    return claims


def read(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.read()


def check(root, claims):
    """The failures, one line each."""
    failures = []
    for n, doc, text, source, regex in claims:
        try:
            src = read(root, source)
            body = read(root, doc)
        except OSError as e:
            failures.append("claim %d: %s" % (n, e))
            continue
        m = re.search(regex, src, re.MULTILINE)
        if not m:
            failures.append("claim %d: %s no longer matches /%s/ (the claim in %s needs a new "
                            "source)" % (n, source, regex, doc))
            continue
        expected = text.replace("{}", m.group(1))
        if expected not in body:
            prefix, suffix = text.split("{}")
            found = re.search(re.escape(prefix) + r"(\S+?)" + re.escape(suffix), body)
            was = (" (it says %s)" % found.group(1)) if found else ""
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
