#!/usr/bin/env python3
"""Every number a person reads goes through one formatting module (issue 48).

  number_text.py ROOT

The module is the files whose names contain "format" (control/common/number_format.*, the
label and table formatters): only they may call the printf family (printf, fprintf, sprintf,
snprintf, vprintf, vfprintf, vsprintf, vsnprintf, dprintf, asprintf, with or without std::) or
{fmt} (fmt::). Reads every .cpp and .hpp below ROOT/{app,sim,control,python} with comments and
string literals blanked; prints each call found elsewhere as "file:line: CALL" and exits 1 if
there is one. Dear ImGui's text calls (ImGui::Text, TextWrapped, TextDisabled, TextColored,
SetTooltip, BulletText) format printf-style too: a format string of theirs with a number
conversion (%d, %.2f, %zu ...) counts as such a call; "%s" of a formatted string does not.
A widget's own display format (SliderFloat's "%.2f") is the widget's, not text, and is left.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from function_length import blank_literals  # noqa: E402

IMGUI_TEXT = re.compile(r'ImGui::(?:Text|TextWrapped|TextDisabled|TextColored|SetTooltip|BulletText)'
                        r'\((?:[^;"()]|\([^;()]*\))*?"((?:[^"\\\n]|\\.)*)"', re.S)
NUMBER_CONVERSION = re.compile(r"%[-+ #0-9.*]*(?:hh|h|ll|l|z|j|t|L)?[dfFgGeEiuxXoc]")
CALL = re.compile(r"(?<![\w.>])(?:std::)?(v?s?n?printf|v?fprintf|dprintf|v?asprintf)\s*\(|\bfmt::\w+")


def main(argv):
    root = argv[1]
    bad = []
    files = 0
    for top in ("app", "sim", "control", "python"):
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            for f in sorted(names):
                if not f.endswith((".cpp", ".hpp")):
                    continue
                files += 1
                if "format" in f:
                    continue
                p = os.path.join(dirpath, f)
                text = open(p, encoding="utf-8", errors="replace").read()
                for m in IMGUI_TEXT.finditer(text):
                    if NUMBER_CONVERSION.search(m.group(1).replace("%%", "")):
                        line = text.count("\n", 0, m.start()) + 1
                        bad.append(f"{os.path.relpath(p, root)}:{line}: ImGui text with "
                                   f"\"{m.group(1)}\"")
                code = blank_literals(text)
                for n, line in enumerate(code.split("\n"), 1):
                    for m in CALL.finditer(line):
                        bad.append(f"{os.path.relpath(p, root)}:{n}: {m.group(0).rstrip('( ')}")
    if files == 0:
        print("no sources found below", root)
        return 1
    for b in bad:
        print(b)
    print(f"{files} files read; {len(bad)} printf-family or fmt:: calls outside the formatting "
          "module (files named *format*)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
