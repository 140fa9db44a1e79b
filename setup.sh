#!/usr/bin/env bash
# Installs shadowlab's Debian 12 build dependencies when any is missing, then configures and
# builds into ./build (Release). Idempotent: with everything installed it only runs an
# incremental build. Usage: bash setup.sh [--tests]
# --tests also installs what only the tests need: snakemake (about 145 Python packages, for the
# workflow test of workflows/) and libsimde-dev (headers only, for the emulated-SIMD test build
# that runs the AVX-512 kernels on machines without AVX-512: docs/testing.md) and PyTorch
# (CPU), numpy and pytest (the network's training tests, tools/nsm/run_tests.sh), and builds the
# Python module (pybind11-dev, python3-matplotlib for its example: docs/python.md), so the main
# command's first run stays lean.
set -euo pipefail
cd "$(dirname "$0")"

options=()
packages=(cmake g++ make pkg-config libembree-dev libtbb-dev libglm-dev libopenexr-dev
          libtinyobjloader-dev libgtest-dev libstb-dev nlohmann-json3-dev libmeshoptimizer-dev
          libcli11-dev libfmt-dev libtinygltf-dev)
if [ "${1:-}" = "--tests" ]; then
  packages+=(snakemake libsimde-dev python3-torch python3-numpy python3-pytest pybind11-dev
             python3-matplotlib)
  options+=(-DSHADOWLAB_PYTHON=ON)
elif [ $# -gt 0 ]; then
  echo "setup.sh: unknown argument '$1' (usage: bash setup.sh [--tests])" >&2
  exit 2
fi
bash tools/install_missing.sh setup "${packages[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${options[@]}" >/dev/null
cmake --build build -j"$jobs"
