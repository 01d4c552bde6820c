"""The generated parts of docs/ are what formsim makes of them today: the scenario catalogue,
the CLI reference and the papers' tables (`scripts/docs_generate.py --check`; the slow papers'
tables are checked by `--check-slow`, see the script; FORMSIM_DOCS_CHECK_SLOW=1 makes this test
use it). Fails with the diff, naming the file."""

import os
import subprocess
import sys

import pytest

from conftest import ROOT


def test_generated_pages_are_current(formsim_bin):
    mode = "--check-slow" if os.environ.get("FORMSIM_DOCS_CHECK_SLOW") == "1" else "--check"
    cmd = [sys.executable, os.path.join(ROOT, "scripts", "docs_generate.py"), mode,
           "--formsim", formsim_bin]
    res = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if res.returncode != 0:
        pytest.fail(f"`{' '.join(cmd)}` failed:\n{res.stderr}{res.stdout}", pytrace=False)
    print(res.stdout, res.stderr)
