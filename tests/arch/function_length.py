#!/usr/bin/env python3
"""No function in app/, sim/ or control/ is longer than a limit (issue 48: 120 lines).

  function_length.py ROOT [--limit N] [--list]

Reads every .cpp and .hpp file below ROOT/{app,sim,control} as text: comments, string and
character literals are blanked, then each brace that opens a function body (the text before it,
back to the last ';', '{' or '}', ends in a parameter list, optionally followed by qualifiers,
a trailing return type or a constructor's initialiser list) is matched with its closing brace.
A function's length is the lines from its signature's first line to that closing brace; a lambda
or local class inside a function counts toward the function. Namespaces, classes, enums and
initialiser braces are not functions. Prints each function over the limit as
"file:line: NAME is N lines (limit L)" and exits 1 if there is one; --list prints every
function's length, longest first.
"""
import os
import re
import sys

KEYWORDS_NOT_FUNCTIONS = ("if", "for", "while", "switch", "catch", "return", "sizeof", "decltype",
                          "alignof", "static_assert", "defined")


def blank_literals(text):
    """Comments, strings and chars replaced by spaces; newlines kept so line numbers hold."""
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
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]{0,16})\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append('"' + re.sub(r"[^\n]", " ", text[i + 1:j - 1]) + '"')
            i = j
        elif c in "\"'":
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum() \
                    and text[i + 2:i + 3] != "'":
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * max(0, j - i - 2) + (c if j - i >= 2 else ""))
            i = j
        elif c == "#" and (i == 0 or text[i - 1] == "\n" or text[:i].rstrip(" \t").endswith("\n")):
            # Preprocessor lines (with continuations) hold no function bodies.
            j = i
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


def head_is_function(head):
    """Whether the text before a '{' is a function's signature; returns its name or None."""
    h = " ".join(head.split())
    if not h or "=" in h.split("(")[0] and not h.split("(")[0].rstrip().endswith("operator="):
        # 'x = {' (initialiser) or 'auto f = [..](..) {' (a lambda at namespace scope counts
        # as a function of its own: handled below).
        m = re.search(r"\[[^\]]*\]\s*(\([^()]*(?:\([^()]*\)[^()]*)*\))?[^()]*$", h)
        if m and "=" in h:
            name = h.split("=")[0].split()[-1] if h.split("=")[0].split() else "lambda"
            return name + " (lambda)"
        return None
    if re.match(r"^(namespace|class|struct|union|enum)\b", h) or re.search(
            r"\b(class|struct|union|enum)\s+[\w:<>, ]*$", h):
        return None
    if re.match(r"^(extern\s+\"C\"|extern)\s*$", h):
        return None
    # Strip a constructor's initialiser list: ') : a_(x), b_{y}' -> ')'.
    m = re.match(r"^(.*?\))\s*(?:const\s*|noexcept\s*(?:\([^)]*\))?|override\s*|final\s*|&\s*|&&\s*|mutable\s*|->\s*[\w:<>,\s*&]+)*(?::.*)?$", h)
    if not m:
        return None
    sig = m.group(1)
    # The name before the parameter list.
    depth = 0
    for k in range(len(sig) - 1, -1, -1):
        if sig[k] == ")":
            depth += 1
        elif sig[k] == "(":
            depth -= 1
            if depth == 0:
                before = sig[:k].rstrip()
                nm = re.search(r"(operator\s*(?:\(\)|[^\s\w(]+|\w[\w\s]*)|~?[\w:]+(?:<[^<>]*>)?)$", before)
                if not nm:
                    return None
                name = nm.group(1)
                last = name.split("::")[-1]
                if last in KEYWORDS_NOT_FUNCTIONS or name in KEYWORDS_NOT_FUNCTIONS:
                    return None
                if before.endswith("]"):
                    return None  # a lambda inside an expression
                return name
    return None


def functions(path):
    text = open(path, encoding="utf-8", errors="replace").read()
    code = blank_literals(text)
    line_of = []
    ln = 1
    for ch in code:
        line_of.append(ln)
        if ch == "\n":
            ln += 1
    stack = []  # (is_function, name, start_offset)
    last_stop = 0
    found = []
    for i, ch in enumerate(code):
        if ch in ";":
            last_stop = i + 1
        elif ch == "{":
            inside_function = any(s[0] for s in stack)
            name = None if inside_function else head_is_function(code[last_stop:i])
            if name:
                # The signature's first line: skip the blank space before it.
                s = last_stop
                while s < i and code[s].isspace():
                    s += 1
                # A template<> line belongs to the function.
                stack.append((True, name, s))
            else:
                stack.append((False, None, i))
            last_stop = i + 1
        elif ch == "}":
            if stack:
                is_fn, name, start = stack.pop()
                if is_fn:
                    found.append((name, line_of[start], line_of[i] - line_of[start] + 1))
            last_stop = i + 1
    return found


def main(argv):
    root = argv[1]
    limit = 120
    listing = "--list" in argv
    if "--limit" in argv:
        limit = int(argv[argv.index("--limit") + 1])
    rows = []
    count = 0
    for top in ("app", "sim", "control"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                if f.endswith((".cpp", ".hpp")):
                    p = os.path.join(dirpath, f)
                    for name, line, length in functions(p):
                        count += 1
                        rows.append((length, os.path.relpath(p, root), line, name))
    if count == 0:
        print("no functions found below", root)
        return 1
    rows.sort(reverse=True)
    if listing:
        for length, p, line, name in rows:
            print(f"{length:5d} {p}:{line}: {name}")
        return 0
    over = [r for r in rows if r[0] > limit]
    for length, p, line, name in over:
        print(f"{p}:{line}: {name} is {length} lines (limit {limit})")
    print(f"{count} functions read; {len(over)} over {limit} lines; the longest is "
          f"{rows[0][3]} at {rows[0][0]} lines ({rows[0][1]}:{rows[0][2]})")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
