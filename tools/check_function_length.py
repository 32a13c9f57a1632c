#!/usr/bin/python3
"""Lists functions longer than a limit (docs/architecture.md, "One vocabulary, short functions").

    /usr/bin/python3 tools/check_function_length.py [--repo REPO] [--max 80] [FOLDER...]

Scans the C++ sources under FOLDER (default: core ui device app report plot) and prints
one line per function body longer than --max lines, signature to closing brace
("FILE:LINE: NAME is N lines"), then exits 1; exits 0 when there is none. A function may
be longer when the comment right above it carries a line starting "Long:" that says why.

The scanner is lexical, not a compiler: it strips comments, strings and character
literals, follows braces, and calls a brace a function body when it opens at namespace or
class scope after a parameter list. A lambda is counted as part of the function around it.
"""

import argparse
import os
import re
import sys

DEFAULT_FOLDERS = ["core", "ui", "device", "app", "report", "plot"]
SOURCES = (".cpp", ".hpp", ".h", ".cc")
SCOPE_WORDS = re.compile(r"^\s*(template\s*<[^{]*>\s*)?(namespace|class|struct|union|enum|extern)\b")
AFTER_PARAMS = re.compile(
    r"(\)|\}|\bconst|\bnoexcept|\boverride|\bfinal|\bmutable|->\s*[\w:<>,\s*&]+)\s*$")
WAIVER = re.compile(r"^\s*//\s*Long:")


def strip_code(text):
    """Text with comments, string and char literals blanked; newlines kept."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + c if j - i >= 2 else " " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """Yields (name, first_line, last_line) of each function body in C++ text."""
    code = strip_code(text)
    code = re.sub(r"^\s*#.*$", lambda m: " " * len(m.group(0)), code, flags=re.M)
    stack = []          # kinds of the open braces: scope, function, block, init
    statement = 0       # where the current statement at this depth began
    starts = []         # (start offset, kind) of the open braces
    for i, c in enumerate(code):
        if c == ";":
            if not stack or stack[-1] in ("scope",):
                statement = i + 1
        elif c == "{":
            prefix = code[statement:i]
            inside_function = any(k in ("function", "block") for k in stack)
            if inside_function:
                kind = "block"
            elif SCOPE_WORDS.match(prefix) and "(" not in prefix.split("{")[0]:
                kind = "scope"
            elif "(" in prefix and AFTER_PARAMS.search(prefix) and "=" not in prefix.split("(")[0]:
                kind = "function"
            else:
                kind = "init"
            stack.append(kind)
            starts.append(statement if kind == "function" else i)
            if kind in ("scope",):
                statement = i + 1
        elif c == "}" and stack:
            kind = stack.pop()
            start = starts.pop()
            if kind == "function":
                yield function_record(code, text, start, i)
            if kind in ("scope", "function") or not stack or stack[-1] == "scope":
                if kind != "init":
                    statement = i + 1


def function_record(code, text, start, end):
    while start < end and code[start].isspace():
        start += 1
    signature = code[start:code.find("(", start)]
    name = signature.split()[-1] if signature.split() else "?"
    first = text.count("\n", 0, start) + 1
    last = text.count("\n", 0, end) + 1
    return name, first, last


def waived(lines, first):
    """True when the comment block right above line `first` has a "Long:" line."""
    k = first - 2
    while k >= 0 and lines[k].strip().startswith("//"):
        if WAIVER.match(lines[k]):
            return True
        k -= 1
    return False


def long_functions(path, limit):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    lines = text.split("\n")
    for name, first, last in functions(text):
        length = last - first + 1
        if length > limit and not waived(lines, first):
            yield name, first, length


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repo", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("--max", type=int, default=80)
    parser.add_argument("folders", nargs="*", default=DEFAULT_FOLDERS)
    args = parser.parse_args()
    found = 0
    for folder in args.folders:
        for root, _, names in os.walk(os.path.join(args.repo, folder)):
            for name in sorted(names):
                if not name.endswith(SOURCES):
                    continue
                path = os.path.join(root, name)
                for fn, line, length in long_functions(path, args.max):
                    rel = os.path.relpath(path, args.repo)
                    print(f"{rel}:{line}: {fn} is {length} lines (limit {args.max})")
                    found += 1
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
