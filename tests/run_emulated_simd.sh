#!/usr/bin/env bash
# Builds the kernel test binaries with every AVX2 and AVX-512 kernel emulated through SIMDe
# (-DSHADOWLAB_EMULATE_SIMD=ON, into build-emu/) and runs them, so the AVX-512 kernels are compared
# with their scalar oracles on a machine without AVX-512 (docs/testing.md). Needs libsimde-dev
# (setup.sh --tests installs it). Usage: bash tests/run_emulated_simd.sh [gtest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
if ! dpkg-query -W -f='${Status}' libsimde-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "run_emulated_simd.sh: libsimde-dev is not installed (run: bash setup.sh --tests)" >&2
  exit 2
fi
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-emu -DCMAKE_BUILD_TYPE=Release -DSHADOWLAB_EMULATE_SIMD=ON >/dev/null
# The four binaries that hold the kernels' tests (the reference's and the programs' exercise
# no kernel these do not), run from the repository root as ctest runs them; their gtest
# arguments pass through (e.g. --gtest_filter=*Simd*).
bins=(test_core test_raster test_techniques test_metric)
cmake --build build-emu -j"$jobs" --target "${bins[@]}"
for b in "${bins[@]}"; do
  echo "run_emulated_simd.sh: $b"
  "build-emu/tests/$b" --gtest_brief=1 "$@"
done
