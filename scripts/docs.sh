#!/usr/bin/env bash
# Builds the documentation site: `mkdocs build --strict` (Debian's mkdocs: apt-get install mkdocs)
# makes site/ from docs/ with README.md as its home page (mkdocs.yml, scripts/mkdocs_hooks.py),
# then checks every link and anchor of the built pages (scripts/docs_site_check.py). A broken
# link, a missing page or image fails. Open site/index.html in a browser.
# Usage: scripts/docs.sh [--site-dir DIR] [other mkdocs build options, e.g. --quiet]
set -euo pipefail
cd "$(dirname "$0")/.."
command -v mkdocs >/dev/null || { echo "docs.sh: mkdocs is missing (apt-get install mkdocs)" >&2; exit 1; }
export PYTHONDONTWRITEBYTECODE=1  # the hook imports scripts/doclinks.py: no scripts/__pycache__
site=site
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case ${args[i]} in
    -d | --site-dir) site=${args[i + 1]:-site} ;;
    --site-dir=*) site=${args[i]#--site-dir=} ;;
  esac
done
mkdocs build --strict --clean "$@"
/usr/bin/python3 scripts/docs_site_check.py "$site"
