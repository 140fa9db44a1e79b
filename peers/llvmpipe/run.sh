#!/usr/bin/env bash
# Builds and runs llvmpipe_bench (docs/llvmpipe.md): installs the EGL and OpenGL packages it
# needs when any is missing (with sudo when not root), turns SHADOWLAB_LLVMPIPE_BENCH on in the
# Release tree build/, builds the one target and runs it with the given flags.
# Usage: bash peers/llvmpipe/run.sh [llvmpipe_bench flags, e.g. --threads 2 --res 1024]
set -euo pipefail
cd "$(dirname "$0")/../.."

packages=(pkg-config libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "llvmpipe: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSHADOWLAB_LLVMPIPE_BENCH=ON >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target llvmpipe_bench >/dev/null
exec build/peers/llvmpipe/llvmpipe_bench "$@"
