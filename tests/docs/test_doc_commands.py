"""Every command the documentation shows runs.

Each fenced block of README.md, CONTRIBUTING.md and docs/**/*.md whose language is sh, bash,
shell or console and whose first command word is `formsim`, `./build/formsim`, `scripts/...`
(also `bash scripts/...`) or `python3` runs as one `bash -e` script (comments and line
continuations as bash reads them; in a console block only the `$ ` lines and their
continuations). Leading VAR=value assignments do not count as the first word.

Marks, on the lines directly above the opening fence:
  <!-- not-run -->                     the block is not run (the window, installs, hours-long runs)
  <!-- test-replace: OLD => NEW -->     the test runs the block with OLD replaced by NEW, the
                                        documented way to shorten a long run (e.g.
                                        `--seeds 1..10 => --seeds 1..2`); several may stack

Where a block runs: a fresh folder per block in which every top-level entry of the repository
is a link to it (so scripts/, assets/, docs/ resolve), build/ is the folder of the formsim
program under test and out/ is empty; `formsim` on PATH is that program, `python3` is the
interpreter running this test (Debian's /usr/bin/python3) with PYTHONPATH=build/python;
DISPLAY is unset. Blocks run FORMSIM_DOCS_JOBS at a time (default: the cores), each with a
timeout of FORMSIM_DOCS_TIMEOUT seconds (default 120). A failing block is named by file:line.
"""

import concurrent.futures
import os
import re
import shlex
import signal
import subprocess
import sys
import tempfile
import threading
import time

import pytest

from conftest import ROOT, formsim_path
import doclinks

LANGS = {"sh", "bash", "shell", "console"}
TIMEOUT = float(os.environ.get("FORMSIM_DOCS_TIMEOUT", "120"))
JOBS = int(os.environ.get("FORMSIM_DOCS_JOBS", "0")) or os.cpu_count() or 1
NOT_RUN = "<!-- not-run -->"
REPLACE = re.compile(r"^<!--\s*test-replace:\s*(?P<old>.+?)\s*=>\s*(?P<new>.*?)\s*-->$")
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")


def command_lines(block):
    """The block's lines as bash runs them (console: the `$ ` commands and their continuations)."""
    lines = block["lines"]
    if block["info"] != "console" or not any(l.startswith("$ ") for l in lines):
        return list(lines)
    out, cont = [], False
    for line in lines:
        if line.startswith("$ ") or cont:
            out.append(line[2:] if line.startswith("$ ") and not cont else line)
            cont = line.rstrip().endswith("\\")
    return out


def first_word(lines):
    for line in lines:
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        try:
            words = shlex.split(s, comments=True)
        except ValueError:
            words = s.split()
        while words and ASSIGNMENT.match(words[0]):
            words = words[1:]
        if words and words[0] in ("bash", "sh") and len(words) > 1:
            return words[0] + " " + words[1]
        return words[0] if words else ""
    return ""


def runnable(word):
    w = word.split()[-1] if word.startswith(("bash ", "sh ")) else word
    if word.startswith(("bash ", "sh ")):
        return w.startswith(("scripts/", "./scripts/"))
    return w in ("formsim", "./build/formsim", "build/formsim", "python3", "/usr/bin/python3") \
        or w.startswith(("scripts/", "./scripts/"))


def marks(text, block):
    """The HTML-comment lines directly above the block's fence."""
    lines = text.split("\n")
    found, i = [], block["start"] - 2
    while i >= 0 and lines[i].strip().startswith("<!--") and lines[i].strip().endswith("-->"):
        found.append(lines[i].strip())
        i -= 1
    return found


def collect():
    """(runnable blocks, blocks marked not-run), each block a dict with id, page, line, script."""
    run, skipped = [], []
    for page in doclinks.repo_pages(ROOT):
        if page == "CHANGELOG.md":
            continue
        with open(os.path.join(ROOT, page), encoding="utf-8") as f:
            text = f.read()
        for block in doclinks.fenced_blocks(text):
            if block["info"] not in LANGS:
                continue
            lines = command_lines(block)
            if not runnable(first_word(lines)):
                continue
            item = {"id": f"{page}:{block['start']}", "page": page, "line": block["start"],
                    "python": first_word(lines) in ("python3", "/usr/bin/python3")}
            block_marks = marks(text, block)
            if NOT_RUN in block_marks:
                skipped.append(item)
                continue
            script = "\n".join(lines)
            for m in block_marks:
                r = REPLACE.match(m)
                if r:
                    if r.group("old") not in script:
                        item["error"] = f"test-replace: `{r.group('old')}` is not in the block"
                    script = script.replace(r.group("old"), r.group("new"))
            item["script"] = script
            run.append(item)
    return run, skipped


BLOCKS, NOT_RUN_BLOCKS = collect()


def shadow_repo(tmp, build_dir):
    """A folder where the repository's entries resolve (links), build/ is build_dir, out/ empty."""
    for name in os.listdir(ROOT):
        if name in ("out", "site") or name.startswith("build"):
            continue
        os.symlink(os.path.join(ROOT, name), os.path.join(tmp, name))
    os.symlink(build_dir, os.path.join(tmp, "build"))
    os.mkdir(os.path.join(tmp, "out"))


def environment(bin_dir, build_dir):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    python_dir = os.path.join(build_dir, "python")
    env["PYTHONPATH"] = os.pathsep.join(p for p in (python_dir, os.environ.get("PYTHONPATH")) if p)
    env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
    env["FORMSIM_BIN"] = os.path.join(bin_dir, "formsim")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def run_block(item, formsim):
    build_dir = os.path.dirname(formsim)
    with tempfile.TemporaryDirectory(prefix="formsim-doc-") as tmp:
        work, bin_dir = os.path.join(tmp, "repo"), os.path.join(tmp, "bin")
        os.mkdir(work)
        os.mkdir(bin_dir)
        shadow_repo(work, build_dir)
        os.symlink(formsim, os.path.join(bin_dir, "formsim"))
        os.symlink(sys.executable, os.path.join(bin_dir, "python3"))
        script = f"set -e\n# {item['id']}\n{item['script']}\n"
        t0 = time.monotonic()
        proc = subprocess.Popen(["bash", "-e", "-c", script], cwd=work, env=environment(bin_dir, build_dir),
                                stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, errors="replace", start_new_session=True)
        try:
            output, _ = proc.communicate(timeout=TIMEOUT)
            rc = proc.returncode
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            output, _ = proc.communicate()
            rc = None
        return {"rc": rc, "output": output, "seconds": time.monotonic() - t0}


_results, _lock = {}, threading.Lock()
_pool = None


@pytest.fixture(scope="module")
def results(request):
    """Starts every selected block at once (JOBS at a time); each test waits for its own."""
    global _pool
    formsim = formsim_path()
    if not os.access(formsim, os.X_OK):
        pytest.fail(f"no formsim program at {formsim} (build it, or set FORMSIM_BIN)")
    selected = [it.callspec.params["block"]["id"] for it in request.session.items
                if hasattr(it, "callspec") and "block" in it.callspec.params]
    _pool = concurrent.futures.ThreadPoolExecutor(max_workers=JOBS)
    by_id = {b["id"]: b for b in BLOCKS}
    for block_id in selected:
        if "error" not in by_id[block_id] and not (by_id[block_id]["python"] and not python_module()):
            _results[block_id] = _pool.submit(run_block, by_id[block_id], formsim)
    yield _results
    _pool.shutdown(wait=True, cancel_futures=True)
    report = sorted(((f.result()["seconds"], k) for k, f in _results.items()
                     if f.done() and not f.cancelled() and f.exception() is None), reverse=True)
    if report:
        total = sum(s for s, _ in report)
        print(f"\ndoc blocks: {len(report)} run, {total:.1f} s of block time; slowest: "
              + ", ".join(f"{k} {s:.1f} s" for s, k in report[:5]))


def python_module():
    """Whether the build made the Python module (FORMSIM_BUILD_PYTHON)."""
    return os.path.isdir(os.path.join(os.path.dirname(formsim_path()), "python", "formsim"))


@pytest.mark.parametrize("block", BLOCKS, ids=[b["id"] for b in BLOCKS])
def test_block_runs(block, results):
    assert "error" not in block, f"{block['id']}: {block.get('error')}"
    if block["python"] and not python_module():
        pytest.skip(f"{block['id']}: the build has no Python module (build/python/formsim)")
    res = results[block["id"]].result()
    tail = "\n".join(res["output"].rstrip().split("\n")[-40:])
    if res["rc"] is None:
        pytest.fail(f"{block['id']}: still running after {TIMEOUT:.0f} s (shorten it with a "
                    f"<!-- test-replace: ... --> mark, or mark it <!-- not-run -->)\n"
                    f"--- block:\n{block['script']}\n--- output (end):\n{tail}", pytrace=False)
    if res["rc"] != 0:
        pytest.fail(f"{block['id']}: exit {res['rc']} after {res['seconds']:.1f} s\n"
                    f"--- block:\n{block['script']}\n--- output (end):\n{tail}", pytrace=False)


def test_there_are_blocks_to_run():
    assert len(BLOCKS) > 0, "no runnable shell block found in README.md and docs/"
