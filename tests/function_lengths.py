#!/usr/bin/env python3
"""Lists the functions and lambdas of the product sources that are longer than a limit.

The rule the code follows: no product function over 100 lines unless its comment says why. This
script measures it. A function's length is counted from the line of its opening brace to the line of
its closing brace, both included. A lambda is counted the same way, and its lines also count towards
the function that holds it.

It reads C++ (.h, .cpp) and GLSL (.glsl) with a small brace matcher, not a compiler: comments,
string and character literals and preprocessor lines are blanked first, then each `{` is classified
by the text before it (function body, lambda body, class or namespace, control block, initializer).

Usage: tests/function_lengths.py [--limit 100] [--all] [paths...]
  paths default to the product folders: skyservice/ weather_ingest/ client_demo/ shaders/.
  Prints "length  kind  file:line  name", longest first; exits 1 when any is over the limit.
"""
import argparse
import os
import re
import sys

PRODUCT_FOLDERS = ["skyservice", "weather_ingest", "client_demo", "shaders"]
SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".glsl", ".comp", ".inl")

CONTROL_WORDS = {"if", "for", "while", "switch", "catch", "do", "else", "try"}
SCOPE_WORDS = re.compile(r"\b(class|struct|union|namespace|enum)\b")
# What may stand between a parameter list's `)` and the body's `{`.
TAIL = re.compile(
    r"\)\s*(?:(?:const|volatile|noexcept(?:\s*\([^()]*\))?|override|final|mutable|constexpr|&&|&)\s*)*"
    r"(?:->\s*[\w:<>,\s\*&]+?)?\s*$")


def blank_non_code(text):
    """Replaces comments, literals and preprocessor lines by spaces, keeping every newline."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            # Preprocessor line, with its backslash continuations.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "\n":
            out.append(c)
            at_line_start = True
            i += 1
            continue
        if c in " \t":
            out.append(c)
            i += 1
            continue
        at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and not (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delim = text[i + 2:open_paren]
            end = text.find(")" + delim + '"', open_paren)
            end = n if end < 0 else end + len(delim) + 2
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:end]))
            i = end
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (j - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching_open_paren(code, close):
    depth = 0
    for k in range(close, -1, -1):
        if code[k] == ")":
            depth += 1
        elif code[k] == "(":
            depth -= 1
            if depth == 0:
                return k
    return -1


def word_before(code, k):
    """The identifier (with :: and ~ and operator spellings) that ends just before index k."""
    j = k
    while j > 0 and code[j - 1].isspace():
        j -= 1
    m = re.search(r"(operator\s*\S+?|~?[A-Za-z_][\w]*(?:\s*::\s*~?[A-Za-z_]\w*)*)\s*$", code[:j])
    return (m.group(1), m.start(1)) if m else ("", j)


def first_top_level_paren(stmt):
    depth = 0
    for k, ch in enumerate(stmt):
        if ch in "<[":
            depth += 1
        elif ch in ">]":
            depth = max(0, depth - 1)
        elif ch == "(" and depth == 0:
            return k
    return -1


def find_blocks(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        code = blank_non_code(f.read())
    line_of = []
    line = 1
    for ch in code:
        line_of.append(line)
        if ch == "\n":
            line += 1

    results = []   # (length, kind, line, name)
    stack = []     # entries: [kind, name, open_index]; kind in function/lambda/scope/other
    stmt_start = 0  # start of the current statement at a non-function scope

    def in_function():
        return any(e[0] in ("function", "lambda") for e in stack)

    def enclosing_function():
        for e in reversed(stack):
            if e[0] in ("function", "lambda"):
                return e[1]
        return ""

    for i, ch in enumerate(code):
        if ch == ";" and not in_function():
            stmt_start = i + 1
        elif ch == "{":
            before = code[:i].rstrip()
            kind, name = "other", ""
            lam_close = None
            if before.endswith("]"):
                lam_close = len(before) - 1
            else:
                m = TAIL.search(before) if before.endswith(")") or re.search(r"[\w>&]\s*$", before) else None
                if m:
                    close = m.start()
                    open_paren = matching_open_paren(code, close)
                    if open_paren > 0 and code[:open_paren].rstrip().endswith("]"):
                        lam_close = len(code[:open_paren].rstrip()) - 1
            if lam_close is not None:
                kind = "lambda"
                depth, k = 0, lam_close
                while k >= 0:
                    if code[k] == "]":
                        depth += 1
                    elif code[k] == "[":
                        depth -= 1
                        if depth == 0:
                            break
                    k -= 1
                m = re.search(r"([A-Za-z_]\w*)\s*=\s*$", code[:k])
                owner = enclosing_function()
                name = (m.group(1) if m else "lambda") + (" in " + owner if owner else "")
            elif not in_function():
                stmt = code[stmt_start:i]
                paren = first_top_level_paren(stmt)
                head = stmt if paren < 0 else stmt[:paren]
                init_list = paren >= 0 and re.search(r"\)\s*[^:]?:[^:]", stmt[paren:]) is not None
                if SCOPE_WORDS.search(head):
                    kind = "other" if re.search(r"\benum\b", head) else "scope"
                elif paren >= 0 and "=" not in head and (TAIL.search(before) or (init_list and before.endswith("}"))):
                    kind = "function"
                    name, _ = word_before(stmt, paren)
                elif re.search(r"\bextern\s*\"\"\s*$", before) or before.endswith("namespace"):
                    kind = "scope"
            else:
                word, _ = word_before(code, i)
                kind = "other"
            stack.append([kind, name, i])
            if kind in ("function", "scope"):
                stmt_start = i + 1
        elif ch == "}":
            if not stack:
                continue
            kind, name, start = stack.pop()
            if kind in ("function", "lambda"):
                results.append((line_of[i] - line_of[start] + 1, kind, line_of[start], name))
            if kind in ("function", "scope") and not in_function():
                stmt_start = i + 1
    return results


def product_files(paths):
    for root in paths:
        if os.path.isfile(root):
            yield root
            continue
        for folder, _, files in os.walk(root):
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.join(folder, name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=100, help="lines a function may have")
    parser.add_argument("--all", action="store_true", help="list every function, not only long ones")
    parser.add_argument("paths", nargs="*")
    args = parser.parse_args()
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    paths = args.paths or [os.path.join(here, p) for p in PRODUCT_FOLDERS]
    rows = []
    for path in product_files(paths):
        rel = os.path.relpath(path, here)
        for length, kind, line, name in find_blocks(path):
            if args.all or length > args.limit:
                rows.append((length, kind, f"{rel}:{line}", name))
    rows.sort(key=lambda r: (-r[0], r[2]))
    for length, kind, where, name in rows:
        print(f"{length:5d}  {kind:8s}  {where}  {name}")
    over = [r for r in rows if r[0] > args.limit]
    print(f"# {sum(1 for r in over if r[1] == 'function')} functions and "
          f"{sum(1 for r in over if r[1] == 'lambda')} lambdas over {args.limit} lines", file=sys.stderr)
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
