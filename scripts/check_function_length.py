#!/usr/bin/env python3
"""Fails when a C++ function of the project is longer than MAX lines (default 60).

    scripts/check_function_length.py REPO_ROOT [--max 60]

A function is counted from the line after its opening brace to the line before its closing
one. The project's clang-format style puts every free function, member function defined out
of its class and test body at column 0, its signature ending in "{" and its body closing
with "}" at column 0; that is what is measured. Functions defined inside a class body are
not (keep them short). A data table (a function that only returns a literal table) is
exempt when the comment block right above it says "(data table)". Run by ctest as
`function_length`.
"""
import argparse
import pathlib
import re
import sys

FOLDERS = ["apps", "bench", "eval", "fuzz", "io", "render", "sensor", "sim", "slam", "tests",
           "types"]
NOT_A_FUNCTION = re.compile(
    r"(namespace\b|struct\b|class\b|enum\b|union\b|extern\b|#|//|using\b|typedef\b|\}"
    r"|template\s*<[^>]*>\s*$)")


def functions(lines):
    """(name line index, first body line index, end line index) of each top-level function."""
    i = 0
    while i < len(lines):
        line = lines[i]
        if line and not line[0].isspace() and not NOT_A_FUNCTION.match(line) and "(" in line \
                and "=" not in line.split("(")[0]:
            k = i
            while k < len(lines) and not lines[k].rstrip().endswith(("{", ";", "}")):
                k += 1
            if k < len(lines) and lines[k].rstrip().endswith("{"):
                j = k + 1
                while j < len(lines) and not lines[j].startswith("}"):
                    j += 1
                yield i, k + 1, j
                i = j
        i += 1


def is_data_table(lines, start):
    i = start - 1
    while i >= 0 and (lines[i].startswith("//") or lines[i].startswith("template")):
        if "(data table)" in lines[i]:
            return True
        i -= 1
    return False


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("root")
    parser.add_argument("--max", type=int, default=60)
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    sources = [p for f in FOLDERS for ext in ("*.cpp", "*.hpp") for p in (root / f).rglob(ext)]
    if len(sources) < 1:
        sys.exit(f"check_function_length: no sources under {root}")
    too_long = []
    for path in sorted(sources):
        lines = path.read_text(encoding="utf-8").split("\n")
        for start, body, end in functions(lines):
            length = end - body
            if length > args.max and not is_data_table(lines, start):
                too_long.append(f"{path.relative_to(root)}:{start + 1}: {length} lines: "
                                f"{lines[start].strip()[:70]}")
    if too_long:
        print(f"Functions over {args.max} lines (split them, or mark a literal table "
              "'(data table)'):\n  " + "\n  ".join(too_long))
        return 1
    print(f"check_function_length: every function of {len(sources)} sources is at most "
          f"{args.max} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
