#!/usr/bin/env python3
"""Counts for scripts/test.sh's closing table, read from what each suite wrote.

  test_counts.py junit FILE [--only PREFIX,...] [--skip PREFIX,...]
      ctest's or pytest's JUnit XML: prints "RUN PASSED FAILED SECONDS" (skipped tests are not
      run; --only / --skip keep or drop the test names starting with a prefix)
  test_counts.py line LOG
      the last "N passed, N failed" line of a log (the browser test's)
  test_counts.py fuzz LOG
      the libFuzzer harnesses of scripts/fuzz.sh's log: each started one is run, each that found
      a failing input failed
  test_counts.py failures FILE...
      the names of the failed tests in ctest's or pytest's JUnit XML files, a line each
      (the table's closing lines, so that a CI log's tail names them)
  test_counts.py table ROWS_FILE
      prints the table of rows "suite<TAB>run<TAB>passed<TAB>failed<TAB>seconds<TAB>note", then
      the closing line "total: N passed, N failed"
"""
import re
import sys
import xml.etree.ElementTree as ET


def junit(files, only=None, skip=None):
    run = passed = failed = 0
    seconds = 0.0
    for f in files:
        try:
            root = ET.parse(f).getroot()
        except (OSError, ET.ParseError):
            continue
        for case in root.iter("testcase"):
            name = case.get("name", "")
            if only and not any(name.startswith(p) for p in only):
                continue
            if skip and any(name.startswith(p) for p in skip):
                continue
            status = case.get("status", "run")
            if status in ("notrun", "disabled") or case.find("skipped") is not None:
                continue
            run += 1
            seconds += float(case.get("time", 0) or 0)
            if status == "fail" or case.find("failure") is not None or case.find("error") is not None:
                failed += 1
            else:
                passed += 1
    return run, passed, failed, seconds


def main(argv):
    mode = argv[1]
    if mode == "junit":
        files, only, skip = [], None, None
        args = iter(argv[2:])
        for a in args:
            if a == "--only":
                only = next(args).split(",")
            elif a == "--skip":
                skip = next(args).split(",")
            else:
                files.append(a)
        run, passed, failed, seconds = junit(files, only, skip)
        print(run, passed, failed, f"{seconds:.0f}")
    elif mode == "line":
        passed = failed = 0
        try:
            for line in open(argv[2], encoding="utf-8", errors="replace"):
                m = re.match(r"^(?:\w+: )?(\d+) passed, (\d+) failed", line.strip())
                if m:
                    passed, failed = int(m.group(1)), int(m.group(2))
        except OSError:
            pass
        print(passed + failed, passed, failed)
    elif mode == "fuzz":
        run = failed = 0
        try:
            for line in open(argv[2], encoding="utf-8", errors="replace"):
                if re.match(r"^fuzz: \w+ for \d+ s$", line.strip()):
                    run += 1
                elif "found a failing input" in line:
                    failed += 1
        except OSError:
            pass
        print(run, run - failed, failed)
    elif mode == "failures":
        for f in argv[2:]:
            try:
                root = ET.parse(f).getroot()
            except (OSError, ET.ParseError):
                continue
            for case in root.iter("testcase"):
                if case.get("status") == "fail" or case.find("failure") is not None or \
                        case.find("error") is not None:
                    print(f"failed: {case.get('name', '?')}  ({f})")
    elif mode == "table":
        rows = [l.rstrip("\n").split("\t") for l in open(argv[2], encoding="utf-8") if l.strip()]
        head = ("suite", "run", "passed", "failed", "seconds", "")
        widths = [max(len(r[i]) for r in rows + [list(head)]) for i in range(5)]
        fmt = lambda r: "  ".join(
            (r[i].ljust(widths[i]) if i == 0 else r[i].rjust(widths[i])) for i in range(5)) + \
            ("  " + r[5] if len(r) > 5 and r[5] else "")
        print(fmt(head))
        print("  ".join("-" * w for w in widths))
        for r in rows:
            print(fmt(r))
        total_p = sum(int(r[2]) for r in rows)
        total_f = sum(int(r[3]) for r in rows) + sum(1 for r in rows if len(r) > 5 and r[5])
        print(f"\ntotal: {total_p} passed, {total_f} failed")
        return 1 if total_f else 0
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
