#!/usr/bin/env bash
# Runs the mutation tool's rule tests (tools/mutate/test_mutants.py; under a second) with a
# python3 that has pytest (/usr/bin/python3's, from python3-pytest, when the first on PATH
# lacks it). No bytecode or pytest cache is written into the tree.
set -euo pipefail
cd "$(dirname "$0")/../.."
py=python3
if ! "$py" -c "import pytest" 2>/dev/null; then
  py=/usr/bin/python3
fi
export PYTHONDONTWRITEBYTECODE=1
exec "$py" -m pytest -q -p no:cacheprovider tools/mutate "$@"
