#!/usr/bin/python3
"""Sizes of the C++ sources against the house rules (files under 600 lines; functions under 80, at most 120).

Usage: /usr/bin/python3 tools/code_size.py [N]   (from the repository root; N = how many of the longest functions)

Functions are found by counting braces after comments and string literals are blanked: a brace that opens after a
closing parenthesis (or const, override, noexcept, a trailing return type or a constructor's initialisers) outside
any function starts one; its length runs from the first line of its signature to its closing brace.
"""
import os
import re
import statistics
import sys

ROOTS = ["models", "planner", "twin", "analysis", "app", "python", "fuzz", "tests"]

# Functions allowed past 120 lines because they are data tables (one entry a few lines, nothing to split out):
# (path, name) -> why.
DATA_TABLES = {
    ("tests/analysis/bad_input_test.cc", "Catalogue"): "the bad-input cases: per case its command, files and expected message",
    ("planner/mesh/generators.cc", "Registry"): "the part generators: per type its parameters (default, range, doc) and builder",
}


def blank(src):
    """`src` with comments and string/char literals emptied, newlines kept."""
    out, i, n = [], 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            i = n if j < 0 else j
        elif src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * src.count("\n", i, j))
            i = j
        elif src.startswith('R"', i) and re.match(r'R"([^(\s]*)\(', src[i:]):
            end = ")" + re.match(r'R"([^(\s]*)\(', src[i:]).group(1) + '"'
            j = src.find(end, i)
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * src.count("\n", i, j))
            i = j
        elif c == '"' or (c == "'" and not (i > 0 and src[i - 1].isalnum())):
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


FUNCTION_HEAD = re.compile(r"\)\s*(const|override|noexcept|final|mutable|->\s*[\w:<>,\s*&]+|\s)*$|\)\s*:\s*.*$")


def functions(path):
    """(length in lines, first line, name) of each function defined in `path`."""
    src = blank(open(path, errors="replace").read())
    found, stack, line, head = [], [], 1, ""
    for c in src:
        if c == "\n":
            line += 1
        if c == "{":
            kind, start, name = "block", line, ""
            if not any(k == "function" for k, _, _ in stack):
                h = re.sub(r"\s+", " ", head.strip())
                if h.startswith("namespace") or h.startswith('extern ""'):
                    kind = "namespace"
                elif re.search(r"\b(class|struct|union|enum)\b[^()]*$", h):
                    kind = "class"
                elif FUNCTION_HEAD.search(h):
                    kind = "function"
                    names = re.findall(r"([~\w:]+)\s*\(", head)
                    name = names[0] if names else "?"
                    start = line - head.strip("\n ").count("\n") - head[len(head.rstrip()):].count("\n")
            stack.append((kind, start, name))
            head = ""
        elif c == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "function":
                    found.append((line - start + 1, start, name))
            head = ""
        elif c == ";":
            head = ""
        else:
            head += c
    return found


def main():
    top = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    files, funcs = [], []
    for root in ROOTS:
        for folder, _, names in os.walk(root):
            for name in sorted(names):
                if name.endswith((".cc", ".h")):
                    path = os.path.join(folder, name)
                    files.append((sum(1 for _ in open(path, errors="replace")), path))
                    funcs += [(n, path, start, fn) for n, start, fn in functions(path)]
    funcs.sort(key=lambda f: (-f[0], f[1], f[2]))
    print(f"{len(files)} files, median {statistics.median(n for n, _ in files):g} lines")
    for n, path in sorted(files, reverse=True):
        if n > 600:
            print(f"file over 600 lines: {path} ({n})")
    print(f"functions over 120 lines: {sum(1 for f in funcs if f[0] > 120)}, over 80: {sum(1 for f in funcs if f[0] > 80)}")
    print(f"the {top} longest functions:")
    for n, path, start, name in funcs[:top]:
        why = DATA_TABLES.get((path, name))
        print(f"{n:5d}  {path}:{start}  {name}" + (f"  (data table: {why})" if why else ""))
    for n, path, start, name in funcs:
        if n > 120 and (path, name) not in DATA_TABLES:
            print(f"function over 120 lines that is not a listed data table: {path}:{start} {name} ({n})")


if __name__ == "__main__":
    main()
