#!/usr/bin/env python3
"""The longest C++ functions in the kit's own code (issue 40: "no function over about 80 lines").

Usage: tests/lab/function_lengths.py [--top N] [--over LINES] [PATH...]

A function's length is its lines from the first line of its signature (template line included)
to its closing brace. Lambdas count inside the function that holds them. Catch2's TEST_CASE,
SCENARIO and SECTION bodies are not functions and are left out. Without PATHs it measures the
places the issue names: common/, viewer/, tests/grader/, tests/support/, tests/feedback/,
tests/check/ and tests/tradeoff/.

It reads the text (comments, strings and preprocessor lines set aside, braces counted), which is
enough for the kit's clang-formatted code; it is a measuring tape, not a compiler.
"""

import argparse
import pathlib
import re
import sys

DEFAULT_PLACES = ["common", "viewer", "tests/grader", "tests/support", "tests/feedback",
                  "tests/check", "tests/tradeoff"]
SUFFIXES = {".cpp", ".hpp", ".h", ".cc", ".cxx", ".ipp"}
NOT_FUNCTIONS = {"TEST_CASE", "TEMPLATE_TEST_CASE", "TEST_CASE_METHOD", "SCENARIO", "SECTION",
                 "TEMPLATE_PRODUCT_TEST_CASE", "METHOD_AS_TEST_CASE"}
KEYWORDS_WITH_PARENS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof",
                        "decltype", "static_assert", "noexcept", "requires"}


def blank_out(text):
    """The text with comments, string and character literals and preprocessor lines replaced by
    spaces (newlines kept), so braces and parentheses can be counted."""
    out = list(text)
    i, n = 0, len(text)
    at_line_start = True

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if at_line_start and c == "#":
            j = i
            while j < n:
                e = text.find("\n", j)
                if e == -1:
                    e = n
                if e > 0 and text[e - 1] == "\\":
                    j = e + 1
                    continue
                break
            blank(i, e)
            i = e
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            e = text.find("\n", i)
            e = n if e == -1 else e
            blank(i, e)
            i = e
        elif text.startswith("/*", i):
            e = text.find("*/", i + 2)
            e = n if e == -1 else e + 2
            blank(i, e)
            i = e
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or
                                                                       text[i - 1] == "_")) or \
                (c in "uUL8" and re.match(r'(u8|u|U|L)R"', text[i:i + 4])
                 and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_"))):
            q = text.index('"', i)
            p = text.index("(", q)
            delimiter = text[q + 1:p]
            e = text.find(")" + delimiter + '"', p)
            e = n if e == -1 else e + len(delimiter) + 2
            blank(i, e)
            i = e
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum()
                                            and text[i - 2:i].isdigit())):
            # A quote after a digit is C++14's digit separator (1'000), not a character literal.
            j = i + 1
            while j < n and text[j] != c:
                if text[j] == "\\":
                    j += 1
                elif text[j] == "\n":
                    break
                j += 1
            blank(i + 1, j)
            i = j + 1
        else:
            i += 1
    return "".join(out)


def function_name(header):
    """The function's name from the text between the previous statement and its body's brace,
    "namespace" or "class" when the brace opens one of those, "init" for a member initialiser's
    brace in a constructor, or None when it opens something else (an initialiser)."""
    h = " ".join(header.split())
    if not h:
        return None
    h = re.sub(r"^template\s*<.*?>\s*(?=[A-Za-z_\[])", "", h)
    h = re.sub(r"__attribute__\s*\(\(.*?\)\)", "", h)
    if re.search(r"\b(namespace|extern)\b", h) and "(" not in h:
        return "namespace"
    first_paren = h.find("(")
    before = h if first_paren < 0 else h[:first_paren]
    if re.search(r"\b(class|struct|union|enum)\b", before) and "=" not in before:
        return "class"
    if first_paren < 0:
        return None
    lam = re.search(r"(\w+)\s*=\s*\[[^\]]*\]\s*$", before)
    if lam:
        return lam.group(1)
    if "=" in before and not re.search(r"operator\s*[^\w\s]*=", before):
        return None
    # The closing parenthesis of the parameter list, then a ':' that is not '::' and a brace
    # right after a name: a member initialiser such as "value_{0}".
    depth, close = 0, -1
    for k in range(first_paren, len(h)):
        if h[k] == "(":
            depth += 1
        elif h[k] == ")":
            depth -= 1
            if depth == 0:
                close = k
                break
    after = h[close + 1:] if close >= 0 else ""
    if re.search(r"(?<!:):(?!:)", after) and re.search(r"[\w>]\s*$", after):
        return "init"
    words = re.findall(r"(operator\s*(?:\(\)|\[\]|[^\w\s(]+)|~?[A-Za-z_]\w*(?:::~?[A-Za-z_]\w*)*)",
                       before)
    if not words:
        return None
    name = words[-1]
    if name.split("::")[-1] in KEYWORDS_WITH_PARENS:
        return None
    return name


def measure(path, text):
    clean = blank_out(text)
    line_of = [0] * (len(clean) + 1)
    line = 1
    for k, ch in enumerate(clean):
        line_of[k] = line
        if ch == "\n":
            line += 1
    line_of[len(clean)] = line
    found = []
    # Stack of scopes: "outer" (namespace, class, file) where functions can start, "skip" inside
    # a function or an initialiser.
    stack = ["outer"]
    header_start = 0
    k, n = 0, len(clean)
    while k < n:
        ch = clean[k]
        if stack[-1] == "outer":
            if ch in ";}":
                if ch == "}":
                    stack.pop() if len(stack) > 1 else None
                header_start = k + 1
            elif ch == "{":
                header = clean[header_start:k]
                name = function_name(header)
                if name in ("namespace", "class"):
                    stack.append("outer")
                    header_start = k + 1
                elif name == "init":
                    depth, j = 0, k
                    while j < n:
                        depth += {"{": 1, "}": -1}.get(clean[j], 0)
                        if depth == 0:
                            break
                        j += 1
                    k = j
                else:
                    # Find the matching brace.
                    depth, j = 0, k
                    while j < n:
                        if clean[j] == "{":
                            depth += 1
                        elif clean[j] == "}":
                            depth -= 1
                            if depth == 0:
                                break
                        j += 1
                    if name and name not in NOT_FUNCTIONS:
                        s = header_start
                        while s < k and clean[s].isspace():
                            s += 1
                        # A label such as "public:" ahead of the signature is not part of it.
                        m = re.match(r"\s*(public|private|protected)\s*:", clean[s:k])
                        if m:
                            s += m.end()
                            while s < k and clean[s].isspace():
                                s += 1
                        first, last = line_of[s], line_of[j]
                        found.append((last - first + 1, name, str(path), first, last))
                    k = j
                    header_start = j + 1
                    # An initialiser's brace is followed by ';' which resets the header anyway.
        k += 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("paths", nargs="*")
    parser.add_argument("--top", type=int, default=10)
    parser.add_argument("--over", type=int, default=None,
                        help="list every function longer than this many lines instead")
    args = parser.parse_args()
    root = pathlib.Path(__file__).resolve().parents[2]
    places = args.paths or [str(root / p) for p in DEFAULT_PLACES]
    files = []
    for place in places:
        p = pathlib.Path(place)
        files += [p] if p.is_file() else sorted(f for f in p.rglob("*") if f.suffix in SUFFIXES)
    found = []
    for f in files:
        found += measure(f.relative_to(root) if f.is_absolute() and root in f.parents else f,
                         f.read_text(encoding="utf-8", errors="replace"))
    found.sort(key=lambda r: (-r[0], r[2], r[3]))
    chosen = [r for r in found if r[0] > args.over] if args.over is not None else found[:args.top]
    for length, name, path, first, last in chosen:
        print(f"{length:5d}  {name}  {path}:{first}-{last}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
