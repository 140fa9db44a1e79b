#!/usr/bin/env bash
# Our forward pass against PyTorch's on the same weights, side by side in one run: ours, then
# PyTorch's three modes (tools/nsm/torch_bench.py), then ours again, then PyTorch again; batch 1,
# fp32, 2 threads, medians of 11 after warm-ups. Also prints the bytes of the activations each
# keeps and a STREAM-like copy's bandwidth at 2 threads.
# Usage: bash tools/nsm/bench_vs_torch.sh [WEIGHTS] [WIDTH] [HEIGHT]   (SHADOWLAB_BUILD: build/)
set -euo pipefail
cd "$(dirname "$0")/../.."
weights=${1:-assets/nsm/default.nsmw}
width=${2:-1024}
height=${3:-768}
build=${SHADOWLAB_BUILD:-build}
py=python3
"$py" -c "import torch" 2>/dev/null || py=/usr/bin/python3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
for round in 1 2; do
  echo "round $round"
  "$build/programs/nsm_forward" --weights "$weights" --width "$width" --height "$height" \
      --threads 2 --repeats 11 --out "$out/ours" | grep -E "^(work|forward)"
  PYTHONDONTWRITEBYTECODE=1 "$py" tools/nsm/torch_bench.py --weights "$weights" --width "$width" \
      --height "$height" --threads 2 --repeats 11
done
