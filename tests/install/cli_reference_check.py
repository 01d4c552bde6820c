#!/usr/bin/env python3
"""ctest install.cli_reference: the man page and the bash completion made at build time
(build/generated/formsim.1, formsim.bash-completion) hold every command and every option that
`formsim COMMAND --help` lists, so neither can drift from the program.
Usage: cli_reference_check.py FORMSIM GENERATED_DIR"""
import re
import subprocess
import sys

formsim, gen = sys.argv[1], sys.argv[2]


def help_of(path):
    out = subprocess.run([formsim, *path, "--help"], capture_output=True, text=True, check=True)
    return out.stdout


def parse(text):
    """The options and the subcommands of one --help text."""
    options, subs, section = set(), [], None
    for line in text.splitlines():
        if re.match(r"^[A-Z][A-Za-z ]*:\s*$", line):
            section = line.strip().rstrip(":")
            continue
        if section == "Subcommands":
            m = re.match(r"^  ([a-z][a-z-]*)\s", line)
            if m:
                subs.append(m.group(1))
        else:
            m = re.match(r"^\s+((?:-\w,)?--[\w-]+(?:,--[\w-]+)*)", line)
            if m:
                options.update(re.findall(r"--[\w-]+|-\w\b", m.group(1)))
    return options, subs


man = open(f"{gen}/formsim.1", encoding="utf-8").read()
completion = open(f"{gen}/formsim.bash-completion", encoding="utf-8").read()
problems, commands, checked = [], [], 0
todo = [[]]
while todo:
    path = todo.pop(0)
    options, subs = parse(help_of(path))
    todo.extend(path + [s] for s in subs)
    if not path:
        continue
    name = " ".join(path)
    commands.append(name)
    # The man page: the command's section and every option in it.
    start = man.find(f'.SS "formsim {name}'.replace("-", "\\-"))
    if start < 0:
        problems.append(f"man page: no section for `formsim {name}`")
        continue
    end = man.find(".SS ", start + 4)
    section = man[start:end if end > 0 else len(man)]
    # The completion: the case entry of the command.
    entry = re.search(r'^    "%s"\)\n(.*?)^      ;;' % re.escape(name), completion, re.M | re.S)
    if not entry:
        problems.append(f"completion: no entry for `formsim {name}`")
    if f'"{" ".join(path[:-1])}/{path[-1]}")' not in completion:
        problems.append(f"completion: `formsim {name}` is not recognised as a command")
    for opt in sorted(options):
        checked += 1
        if opt.replace("-", "\\-") not in section:
            problems.append(f"man page: `formsim {name}` lacks {opt}")
        if entry and not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(opt), entry.group(1)):
            problems.append(f"completion: `formsim {name}` lacks {opt}")

for p in problems:
    print("FAIL:", p)
print(f"{len(commands)} commands, {checked} options checked against --help: "
      f"{len(problems)} problems")
if len(commands) < 10 or checked < 100:
    print("FAIL: too few commands or options were found in --help (its format changed?)")
    sys.exit(1)
sys.exit(1 if problems else 0)
