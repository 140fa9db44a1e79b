#!/usr/bin/env bash
# Regenerates docs/techniques/keys.md from the key declarations (`render --list-keys`; run after
# declaring or changing a key: tests/programs/keys_doc_test.cpp fails while they disagree).
# Usage: bash docs/techniques/keys.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
"$build/programs/render" --list-keys > docs/techniques/keys.md
echo "wrote docs/techniques/keys.md"
