#!/usr/bin/env bash
# Builds and runs llvmpipe_bench (docs/llvmpipe.md): installs the EGL and OpenGL packages it
# needs when any is missing (with sudo when not root), turns SHADOWLAB_LLVMPIPE_BENCH on in the
# Release tree build/, builds the one target and runs it with the given flags.
# Usage: bash peers/llvmpipe/run.sh [llvmpipe_bench flags, e.g. --threads 2 --res 1024]
set -euo pipefail
cd "$(dirname "$0")/../.."

packages=(pkg-config libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri)
bash tools/install_missing.sh llvmpipe "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSHADOWLAB_LLVMPIPE_BENCH=ON >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target llvmpipe_bench >/dev/null
exec build/peers/llvmpipe/llvmpipe_bench "$@"
