#!/usr/bin/env bash
# Runs the NSM training tests (tools/nsm/test_*.py; a few seconds): python3 -m pytest -q
# tools/nsm. They need Debian's python3-torch, python3-numpy and python3-pytest, which live in
# /usr/bin/python3's packages: when the python3 first on PATH lacks them (a pyenv or venv
# interpreter), /usr/bin/python3 runs them. No bytecode or pytest cache is written into the
# tree.
set -euo pipefail
cd "$(dirname "$0")/../.."
py=python3
if ! "$py" -c "import torch, numpy, pytest" 2>/dev/null; then
  py=/usr/bin/python3
fi
export PYTHONDONTWRITEBYTECODE=1
exec "$py" -m pytest -q -p no:cacheprovider tools/nsm "$@"
