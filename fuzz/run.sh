#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (in build-fuzz/, or in the clang -DSHADOWLAB_FUZZ=ON
# tree that SHADOWLAB_FUZZ_BUILD names) and runs each for SECONDS, as many at a time as there are
# cores, on a working copy of its checked-in seed corpus (fuzz/corpus/<name>/). A crash, a hang
# (> 10 s on one input) or an allocation over 2 GB stops the run with a non-zero exit and leaves
# the input in that folder.
# Usage: bash fuzz/run.sh SECONDS [fuzz_obj fuzz_spec fuzz_slide fuzz_exr fuzz_gltf fuzz_scene_file fuzz_json]
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_obj fuzz_spec fuzz_slide fuzz_exr fuzz_gltf fuzz_scene_file fuzz_json)
bdir=${SHADOWLAB_FUZZ_BUILD:-build-fuzz}
if [ -z "${SHADOWLAB_FUZZ_BUILD:-}" ]; then
  cxx=$(command -v clang++-14 || command -v clang++)
  cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
        -DSHADOWLAB_FUZZ=ON >/dev/null
fi
cmake --build "$bdir" -j"$(nproc 2>/dev/null || echo 2)" --target "${targets[@]}" >/dev/null
# The targets run as many at a time as there are cores (each libFuzzer process is one thread);
# their results are reported in target order.
jobs=$(nproc 2>/dev/null || echo 2)
run_one() {
  local t=$1
  (cd "$bdir" && ./fuzz/"$t" -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 \
     -print_final_stats=1 "corpus/$t" >"$t.log" 2>&1)
  echo $? > "$bdir/$t.rc"
}
for t in "${targets[@]}"; do
  corpus=$bdir/corpus/$t
  mkdir -p "$corpus"
  cp -n fuzz/corpus/"${t#fuzz_}"/* "$corpus"/ 2>/dev/null || true
  rm -f "$bdir/$t.rc"
  run_one "$t" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
done
wait
for t in "${targets[@]}"; do
  log=$bdir/$t.log
  if [ "$(cat "$bdir/$t.rc" 2>/dev/null || echo 1)" != 0 ]; then
    echo "fuzz: $t FAILED (see $log and the crash-*/timeout-*/oom-* input in $bdir/)" >&2
    tail -n 30 "$log" >&2
    exit 1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*')
  echo "fuzz: $t ran ${secs}s: $execs executions, coverage $cov edges, no crash"
done
