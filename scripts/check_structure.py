#!/usr/bin/env python3
"""Checks the source tree's shape: function and file lengths, and that each
layer includes only the layers below it.

    scripts/check_structure.py [--max-function N] [--max-file N] [SRC_DIR]

Parameter lists are not counted: a function takes what it reads, and a
struct holds values that belong together (PathContext, PathState), not a
bundle made to shorten one signature.

Exit 0 when everything holds, 1 with one line per violation otherwise.
Functions are found by brace matching: a '{' at namespace or class scope
whose declaration holds a '(' opens a function body; lambdas and local
classes count toward the function around them.
"""
import argparse
import pathlib
import re
import sys

# Each layer may include itself and the layers listed for it: geometry <
# scene < render < io (the file formats, which write render's types), with
# app and viewer on top.
LAYERS = {
    "geometry": {"geometry"},
    "scene": {"geometry", "scene"},
    "render": {"geometry", "scene", "render"},
    "io": {"geometry", "scene", "render", "io"},
    "app": {"geometry", "scene", "render", "io", "app", "viewer"},
    "viewer": {"geometry", "scene", "render", "io", "viewer"},
}


def strip_comments_and_strings(text):
    """Blanks comments, string and char literals, keeping newlines."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(n, j + 1)
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(text):
    """Yields (name, first_line, line_count) of each function body."""
    code = strip_comments_and_strings(text)
    stack = []  # 'scope' (namespace/class) or ('fn', name, line) or 'block'
    decl_start = 0
    for i, c in enumerate(code):
        if c in ";":
            if not stack or stack[-1] == "scope":
                decl_start = i + 1
        elif c == "{":
            if not stack or stack[-1] == "scope":
                decl = code[decl_start:i]
                flat = " ".join(decl.split())
                if re.search(r"\b(namespace|struct|class|union|enum)\b[^()]*$", flat) or \
                        re.match(r'^extern\s*$', flat) or "(" not in flat or \
                        re.search(r"=\s*$", flat):
                    stack.append("scope" if "(" not in flat or re.search(
                        r"\b(namespace|struct|class|union|enum)\b", flat) else "block")
                else:
                    m = re.findall(r"([~\w:]+)\s*\(", flat)
                    name = m[0] if m else "?"
                    stack.append(("fn", name, code.count("\n", 0, i) + 1))
            else:
                stack.append("block")
            decl_start = i + 1
        elif c == "}":
            top = stack.pop() if stack else None
            if isinstance(top, tuple):
                end = code.count("\n", 0, i) + 1
                yield top[1], top[2], end - top[2] + 1
            if not stack or stack[-1] == "scope":
                decl_start = i + 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-function", type=int, default=100)
    ap.add_argument("--max-file", type=int, default=450)
    ap.add_argument("src", nargs="?",
                    default=str(pathlib.Path(__file__).resolve().parent.parent / "src"))
    args = ap.parse_args()
    src = pathlib.Path(args.src)
    problems = []
    for f in sorted(src.rglob("*")):
        if f.suffix not in (".h", ".hpp", ".cpp"):
            continue
        rel = f.relative_to(src)
        text = f.read_text(encoding="utf-8")
        lines = text.count("\n")
        if lines > args.max_file:
            problems.append(f"{rel}: {lines} lines (limit {args.max_file})")
        for name, line, count in functions(text):
            if count > args.max_function:
                problems.append(f"{rel}:{line}: function {name} is {count} lines "
                                f"(limit {args.max_function})")
        layer = rel.parts[0]
        allowed = LAYERS.get(layer)
        if allowed is None:
            continue
        for n, l in enumerate(text.splitlines(), 1):
            m = re.match(r'\s*#\s*include\s*["<]([^">]+)[">]', l)
            if not m:
                continue
            target = m.group(1)
            if target.startswith("."):  # relative: where it lands in src
                landed = (f.parent / target).resolve()
                if src.resolve() in landed.parents:
                    target = landed.relative_to(src.resolve()).as_posix()
            used = target.split("/")[0]
            if used in LAYERS and used not in allowed:
                problems.append(f"{rel}:{n}: {layer} includes {used}/ (allowed: "
                                f"{', '.join(sorted(allowed))})")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
