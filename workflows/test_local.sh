#!/usr/bin/env bash
# The workflow's local run, as a test (ctest Workflow.LocalRunEqualsOneProcess): snakemake -j2 on
# a tiny space with 3 shards from an empty cache, then the same tune in one process; every
# evaluation's scores and work counts must be identical, bit for bit.
# Usage: bash workflows/test_local.sh BUILD_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: test_local.sh BUILD_DIR}" && pwd)
command -v snakemake >/dev/null || { echo "snakemake is missing: run bash setup.sh --tests" >&2; exit 1; }
work=$build/test_output/workflow
rm -rf "$work"
mkdir -p "$work"
args="--space 'csm:res=32..128/x2,pcf=1|3' --space 'cvsm:res=32|64' --width 96 --height 72 --spp 8 --repeats 1 --budget-ms 1,4,16"
cat > "$work/config.yaml" <<YAML
build: $build
out: $work/out
cache: $work/cache
shards: 3
threads: 1
scenes: [default]
args: "$args"
YAML
(cd "$work" && snakemake -j2 -q -s "$root/workflows/Snakefile" --configfile "$work/config.yaml" >"$work/snakemake.log" 2>&1) ||
  { tail -n 30 "$work/snakemake.log" >&2; exit 1; }
eval "SHADOWLAB_CACHE=$work/cache $build/programs/tune $args --threads 2 --out $work/single" >/dev/null
python3 - "$work/single/tune.json" "$work/out/default/tune.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))["evaluations"]
b = json.load(open(sys.argv[2]))["evaluations"]
keys = ["spec", "objective", "c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail",
        "fidelity", "aesthetics", "total", "ssim", "rmse", "psnr", "work"]
assert len(a) == len(b) == 8, (len(a), len(b))
for x, y in zip(a, b):
    for k in keys:
        assert x[k] == y[k], (x["spec"], k, x[k], y[k])
print("workflow: 3 shards merged, 8 evaluations equal to one process's")
PY
