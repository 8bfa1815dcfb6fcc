#!/usr/bin/env python3
"""The house's size limits, checked in CI (.ci/run):
- in the libraries (core, perception, robots, servo, tsrrt): no function over 120 lines, no
  source or header file over 600 lines;
- README.md at most 400 lines.
A function is a top-level brace block outside namespaces, classes and structs (a member function
defined in a class body counts with its class). Exit 1 listing every breach, 0 otherwise.
Usage: .ci/check_limits.py [REPO]"""
import pathlib
import re
import sys

LIBRARIES = ("core", "perception", "robots", "servo", "tsrrt")
MAX_FUNCTION, MAX_FILE, MAX_README = 120, 600, 400


def code(line):
    """The line without string and character literals and // comments."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def long_functions(path):
    lines = path.read_text().split("\n")
    stack, start = [], None
    for i, raw in enumerate(lines):
        line = code(raw)
        for ch in line:
            if ch == "{":
                scope = re.match(r"^\s*(namespace|struct|class|enum|union)\b", line) is not None
                if not scope and start is None and all(stack):
                    start = i
                stack.append(scope)
            elif ch == "}" and stack:
                scope = stack.pop()
                if not scope and start is not None and all(stack):
                    if i - start > MAX_FUNCTION:
                        yield start + 1, i - start, lines[start].strip()
                    start = None


def main():
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    breaches = []
    for lib in LIBRARIES:
        for path in sorted((repo / lib).glob("*.[ch]pp")):
            count = path.read_text().count("\n")
            if count > MAX_FILE:
                breaches.append(f"{path}: {count} lines (at most {MAX_FILE})")
            for line, length, text in long_functions(path):
                breaches.append(
                    f"{path}:{line}: a function of {length} lines (at most {MAX_FUNCTION}): {text}")
    readme = (repo / "README.md").read_text().count("\n")
    if readme > MAX_README:
        breaches.append(f"README.md: {readme} lines (at most {MAX_README})")
    for b in breaches:
        print(b)
    print(f"check_limits: {len(breaches)} breaches")
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
