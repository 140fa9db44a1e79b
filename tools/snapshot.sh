#!/usr/bin/env bash
# Pixel checksums of every technique and mode, for proving that a refactor keeps the same bits.
#
# Renders every layout x filter (on the cube layout each filter's kernel-selecting keys too: blur
# widths with and without compiled fixed-width kernels, the fp32/slope/quantize16/hausdorff/
# moments variants, PCF grid/Poisson/rpdb, seams, depth formats) and the ray-traced reference on
# the default, foliage and room100k scenes at 256x192, once per instruction set this CPU runs:
# the widest (default), SHADOWLAB_ISA=avx2, and SHADOWLAB_SCALAR=1 (the scalar oracles). Prints
# one line per render, "<isa> <scene> <technique> <md5 of mask.exr's pixels> <the same of
# texel.exr, or ->" (tools/exr_pixels_md5.py: the EXR headers carry the command, commit and
# date, which differ between runs; the pixels' compressed chunks do not), in a fixed order.
#
# Usage: bash tools/snapshot.sh [BUILD_DIR] > snapshot.txt   (BUILD_DIR: build by default;
# SNAPSHOT_JOBS renders at once, 3 by default). Compare two runs with diff: a differing line
# names the technique and mode that changed.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ ${1:-} == --one ]]; then  # one render: --one BUILD_DIR INDEX MODE SCENE TECHNIQUE [FLAGS]
  build=$2 index=$3 mode=$4 scene=$5 tech=$6
  shift 6
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
  env=()
  case $mode in
    avx2) env=(SHADOWLAB_ISA=avx2) ;;
    scalar) env=(SHADOWLAB_SCALAR=1) ;;
  esac
  if ! env "${env[@]}" "$build/programs/render" --scene "$scene" --width 256 --height 192 \
      --threads 2 --repeats 1 --technique "$tech" --out "$out/run" "$@" >/dev/null 2>"$out/err"; then
    echo "$index $mode $scene $tech FAILED: $(head -1 "$out/err")"
    exit 0
  fi
  texel=-
  mask=$(python3 tools/exr_pixels_md5.py "$out/run/mask.exr")
  [[ -f "$out/run/texel.exr" ]] && texel=$(python3 tools/exr_pixels_md5.py "$out/run/texel.exr")
  echo "$index $mode $scene $tech $mask $texel"
  exit 0
fi

build=${1:-build}
[[ -x "$build/programs/render" ]] || { echo "snapshot.sh: $build/programs/render: not built" >&2; exit 2; }

# Every filter on every layout; on the cube the keys that choose different kernels too.
filters=(sm vsm esm evsm msm pcss)
cube_keys=(
  "sm:pcf=3" "sm:pcf=5,pcf_kind=poisson" "sm:pcf=3,rpdb=1" "sm:seams=guard,pcf=3" "sm:depth=16"
  "sm:depth=8cubic" "vsm:blur=1" "vsm:blur=9" "vsm:blur=13" "vsm:fp32=1" "vsm:slope_moment=1"
  "vsm:maxdepth_eps=0.01" "vsm:bleed=0.2" "esm:blur=1" "esm:blur=7" "esm:blur=11" "esm:c=80"
  "evsm:moments=4" "evsm:blur=5" "evsm:blur=13" "evsm:moments=4,blur=1" "msm:quantize16=1"
  "msm:variant=hausdorff" "msm:blur=5" "msm:blur=9" "msm:blur=15" "msm:blur=1" "pcss:rpdb=1"
  "pcss:estimate=model"
)
techniques=()
for layout in c t d; do
  for f in "${filters[@]}"; do techniques+=("$layout$f"); done
done
for k in "${cube_keys[@]}"; do techniques+=("c$k"); done
techniques+=("tsm:pcf=3" "tvsm:blur=5" "tevsm:moments=4" "tmsm:quantize16=1" "dsm:pcf=3"
             "dsm:tess=32" "dvsm:blur=5" "devsm:moments=4" "dmsm:quantize16=1" "rt:spp=4"
             "rt:hard=1")
# The projector layout needs a slide projector light.
projector=(psm "psm:pcf=3" pvsm pesm pevsm "pevsm:moments=4" pmsm "pmsm:quantize16=1" ppcss)

jobs() {
  local i=0
  for mode in default avx2 scalar; do
    for scene in default foliage room100k; do
      for tech in "${techniques[@]}"; do printf '%s\n' "$((i++)) $mode $scene $tech"; done
      for tech in "${projector[@]}"; do printf '%s\n' "$((i++)) $mode $scene $tech --slide spot"; done
    done
  done
}
jobs | xargs -P "${SNAPSHOT_JOBS:-3}" -L 1 bash tools/snapshot.sh --one "$build" |
  sort -n | cut -d' ' -f2-
