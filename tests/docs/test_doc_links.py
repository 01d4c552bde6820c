"""Every relative link and image of README.md, CONTRIBUTING.md, CHANGELOG.md and docs/**/*.md
resolves to a file or folder of the repository that git does not ignore, and an anchor into a
Markdown page (page.md#anchor, or #anchor on the same page) names one of its headings (GitHub's
anchors; the site uses the same, see scripts/mkdocs_hooks.py)."""

import os
import posixpath

import pytest

from conftest import ROOT
import doclinks

PAGES = doclinks.repo_pages(ROOT)


def read(page):
    with open(os.path.join(ROOT, page), encoding="utf-8") as f:
        return f.read()


def test_there_are_pages():
    assert "README.md" in PAGES and any(p.startswith("docs/") for p in PAGES)


@pytest.mark.parametrize("page", PAGES)
def test_links_resolve(page):
    text = read(page)
    problems, targets = [], {}
    for link in doclinks.links(text):
        target = link["target"]
        where = f"{page}:{link['line']}: `{target}`"
        if target.startswith("#"):
            if target[1:] not in doclinks.anchors(text):
                problems.append(f"{where}: no heading or anchor `{target}` on this page")
            continue
        if not doclinks.is_relative(target):
            if target.startswith("/"):
                problems.append(f"{where}: an absolute path (resolves nowhere on GitHub or the site)")
            continue
        path, fragment = doclinks.split_target(target)
        resolved = posixpath.normpath(posixpath.join(posixpath.dirname(page), path))
        if resolved.startswith("../") or resolved == "..":
            problems.append(f"{where}: leads out of the repository")
            continue
        full = os.path.join(ROOT, resolved)
        if not os.path.exists(full):
            problems.append(f"{where}: {resolved} does not exist")
            continue
        targets.setdefault(resolved, []).append(where)
        if fragment and resolved.endswith(".md") and os.path.isfile(full):
            if fragment not in doclinks.anchors(read(resolved)):
                problems.append(f"{where}: {resolved} has no heading or anchor `#{fragment}`")
    for ignored in sorted(doclinks.git_ignored(ROOT, sorted(targets))):
        problems += [f"{w}: {ignored} is ignored by git (not in the repository)" for w in targets[ignored]]
    if problems:
        pytest.fail("\n".join(problems), pytrace=False)
