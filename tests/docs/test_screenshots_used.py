"""The pictures and the project files the pages promise:
- every PNG under screenshots/ (the scenario thumbnails too) is shown or linked by README.md or a
  page of docs/, and every image a page shows exists (test_doc_links checks every link);
- every shipped scenario and lesson is named in docs/;
- README.md has at most 200 lines;
- CITATION.cff is YAML with cff-version 1.2.0 and references."""

import os
import posixpath

import pytest
import yaml

from conftest import ROOT
import doclinks

PAGES = [p for p in doclinks.repo_pages(ROOT) if p == "README.md" or p.startswith("docs/")]


def read(path):
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def linked_files():
    """{repository path: [page:line, ...]} of every relative link and image of the pages."""
    used = {}
    for page in PAGES:
        for link in doclinks.links(read(page)):
            if doclinks.is_relative(link["target"]):
                path, _ = doclinks.split_target(link["target"])
                resolved = posixpath.normpath(posixpath.join(posixpath.dirname(page), path))
                used.setdefault(resolved, []).append(f"{page}:{link['line']}")
    return used


def test_every_screenshot_is_used():
    used = linked_files()
    pngs = []
    for d, dirs, files in os.walk(os.path.join(ROOT, "screenshots")):
        dirs.sort()
        pngs += sorted(os.path.relpath(os.path.join(d, f), ROOT).replace(os.sep, "/")
                       for f in files if f.lower().endswith(".png"))
    assert pngs, "no PNG under screenshots/"
    unused = [p for p in pngs if p not in used]
    assert not unused, ("PNGs shown by no page (show them in README.md or docs/, or delete them):\n"
                        + "\n".join(unused))


def test_every_page_image_exists():
    missing = []
    for page in PAGES:
        for link in doclinks.links(read(page)):
            if link["image"] and doclinks.is_relative(link["target"]):
                path, _ = doclinks.split_target(link["target"])
                resolved = posixpath.normpath(posixpath.join(posixpath.dirname(page), path))
                if not os.path.isfile(os.path.join(ROOT, resolved)):
                    missing.append(f"{page}:{link['line']}: {link['target']}")
    assert not missing, "images that do not exist:\n" + "\n".join(missing)


def shipped(folder):
    d = os.path.join(ROOT, "assets", folder)
    return sorted(f[:-5] for f in os.listdir(d) if f.endswith(".yaml"))


@pytest.mark.parametrize("folder", ["scenarios", "lessons"])
def test_every_shipped_scenario_is_named_in_docs(folder):
    docs_text = "\n".join(read(p) for p in PAGES if p.startswith("docs/"))
    names = shipped(folder)
    assert names
    missing = [n for n in names if n not in docs_text]
    assert not missing, f"assets/{folder} named nowhere in docs/: {', '.join(missing)}"


def test_readme_is_short():
    n = len(read("README.md").splitlines())
    assert n <= 200, f"README.md has {n} lines (at most 200)"


def test_citation_cff():
    path = os.path.join(ROOT, "CITATION.cff")
    assert os.path.isfile(path), "CITATION.cff is missing"
    with open(path, encoding="utf-8") as f:
        cff = yaml.safe_load(f)
    assert isinstance(cff, dict)
    assert str(cff.get("cff-version")) == "1.2.0"
    for key in ("message", "title", "authors"):
        assert cff.get(key), f"CITATION.cff has no {key}"
    refs = cff.get("references")
    assert isinstance(refs, list) and refs, "CITATION.cff names no references (the seed papers)"
    for ref in refs:
        assert ref.get("type") and ref.get("title") and ref.get("authors"), ref
