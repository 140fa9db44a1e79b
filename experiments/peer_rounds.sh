#!/usr/bin/env bash
# The rasterizer's jobs, shadowlab and Mesa's llvmpipe interleaved in one run
# (docs/performance_history.md): ROUNDS rounds of every job, each printing "who job median_ms".
#   bash experiments/peer_rounds.sh PATH/TO/gl_bench [ROUNDS]
# gl_bench is the peer of ../shared/peers/llvmpipe/ (built outside the project tree, as its
# README says). Run from the repository root after the build.
set -euo pipefail
lp=${1:?usage: peer_rounds.sh PATH/TO/gl_bench [ROUNDS]}
rounds=${2:-3}
[ -x "$lp" ] || { echo "peer_rounds.sh: $lp: not an executable" >&2; exit 2; }
rb=build/experiments/raster_bench
obj=../shared/assets/bench/room100k.obj
[ -x "$rb" ] || { echo "peer_rounds.sh: $rb: build first" >&2; exit 2; }
[ -f "$obj" ] || { echo "peer_rounds.sh: $obj: not found" >&2; exit 2; }
ours() { "$rb" "$@" 2>&1 | sed -n 's/.*median *\([0-9.]*\).*/\1/p'; }
ratio() { "$rb" --scaling "$@" 2>&1 | sed -n 's/.*ratio median *\([0-9.]*\).*/\1/p'; }
peer() { LP_NUM_THREADS=2 "$lp" "$@" 2>&1; }
med() { sed -n "s/.*$1.*ms_med=\([0-9.]*\).*/\1/p"; }
for ((i = 0; i < rounds; ++i)); do
  for res in 512 1024 2048; do
    echo "ours cube$res $(ours --scene "$obj" --threads 2 --repeats 11 --res "$res" --only cube)"
    echo "llvmpipe cube$res $(peer --tris 100k --sizes "$res" --objcull 0 --runs 7 | med 'cube_depth')"
  done
  echo "ours gbuffer $(ours --scene "$obj" --threads 2 --repeats 11 --only gbuffer)"
  echo "llvmpipe camera_noshadow $(peer --tris 100k --sizes 1024 --objcull 0 --runs 7 --camera 1 | med 'camera_noshadow')"
  echo "ours cube1m $(ours --scene room1m --threads 2 --repeats 11 --only cube)"
  echo "llvmpipe cube1m $(peer --tris 1m --sizes 1024 --objcull 0 --runs 5 | med 'cube_depth')"
  # 1 -> 2 thread scaling: raster_bench --scaling alternates the two counts repeat by repeat
  # and prints the median of the per-repeat ratios ("scaling-JOB ratio").
  for job in cube gbuffer lookup; do
    echo "ours scaling-$job $(ratio --scene "$obj" --threads 2 --repeats 11 --only "$job")"
  done
  echo "ours scaling-cube1m $(ratio --scene room1m --threads 2 --repeats 11 --only cube)"
done
