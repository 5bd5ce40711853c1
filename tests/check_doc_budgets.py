#!/usr/bin/python3
"""The README and the reference documents stay within their byte budgets.

usage: check_doc_budgets.py [SOURCE_DIR]

The documents describe the present: the method, the current numbers and how
to reproduce them; history lives in the commit messages. Their budgets keep
dated journals from growing back. The check prints each file's size and
budget, and fails (exit 1, one line per file over its budget, or missing,
naming it) when any is over. No dependencies beyond the standard library.
"""
import os
import sys

BUDGETS = [
    ("README.md", 15000),
    ("docs/performance.md", 25000),
    ("docs/verification.md", 40000),
    ("docs/method.md", 60000),
]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    problems = []
    for name, budget in BUDGETS:
        path = os.path.join(root, name)
        try:
            size = os.path.getsize(path)
        except OSError:
            print(f"{name}: missing (budget {budget:,} bytes)")
            problems.append(f"{name}: missing")
            continue
        print(f"{name}: {size:,} bytes (budget {budget:,})")
        if size > budget:
            problems.append(f"{name}: {size:,} bytes, over its budget of {budget:,} by {size - budget:,}")
    for line in problems:
        print(line, file=sys.stderr)
    if problems:
        print(f"{len(problems)} document(s) over budget or missing", file=sys.stderr)
        return 1
    print("every document within its budget")
    return 0


if __name__ == "__main__":
    sys.exit(main())
