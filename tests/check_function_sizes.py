#!/usr/bin/python3
"""No function in src/ or problems/ is longer than 100 lines.

usage: check_function_sizes.py [SOURCE_DIR]

A function at namespace level (a free function, or a member defined outside
its class) is measured from the line of its opening brace to that of its
closing one; comments and string literals are blanked first so that their
braces do not count. A class defined at namespace level is measured as one
block, which keeps its inline members short too. Exit 1 with one line per
function over the limit, naming file, line and length.
"""
import glob
import os
import re
import sys

LIMIT = 100


def code_lines(text):
    """The file's lines with comments and string and character literals blanked."""
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    lines = []
    for line in text.split("\n"):
        line = re.sub(r'"([^"\\]|\\.)*"', '""', line)
        line = re.sub(r"'([^'\\]|\\.)*'", "''", line)
        lines.append(re.sub(r"//.*", "", line))
    return lines


def long_functions(path):
    lines = code_lines(open(path, encoding="utf-8").read())
    stack = []  # per open brace: True for a namespace or extern "C" block
    start = None
    for number, line in enumerate(lines, 1):
        for char in line:
            if char == "{":
                namespace = bool(re.match(r"\s*(namespace\b|extern \"C\")", line))
                if not namespace and start is None and all(stack):
                    start = number
                stack.append(namespace)
            elif char == "}":
                if stack:
                    stack.pop()
                if start is not None and all(stack):
                    length = number - start + 1
                    if length > LIMIT:
                        yield start, length
                    start = None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    files = sorted(glob.glob(os.path.join(root, "src", "**", "*.[ch]pp"), recursive=True) +
                   glob.glob(os.path.join(root, "problems", "*.[ch]pp")))
    over = [f"{os.path.relpath(path, root)}:{line}: {length} lines (limit {LIMIT})"
            for path in files for line, length in long_functions(path)]
    for line in over:
        print(line, file=sys.stderr)
    if over:
        return 1
    print(f"{len(files)} files: no function over {LIMIT} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
