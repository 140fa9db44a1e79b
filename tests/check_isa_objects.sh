#!/usr/bin/env bash
# Fails when an object compiled for AVX2 or AVX-512 (*_avx2.cpp.o, *_avx512.cpp.o) holds a fused
# multiply-add: the ISA files are compiled with -mfma, and only -ffp-contract=off keeps the
# compiler from contracting a multiply and an add into one rounding, which would give other
# bits than the scalar oracles (docs/simd.md). Outside the allow-list below no kernel calls an FMA
# intrinsic, so any vfmadd / vfmsub / vfnmadd / vfnmsub (every form: 132, 213, 231, ps, pd, ss,
# sd, addsub) is one.
# The allow-list: the NSM network's convolution rows (techniques/nsm/nsm_conv_*.cpp) call
# vfmadd explicitly, and their scalar oracle calls std::fma in the same order: one rounding each,
# the same bits (docs/simd.md "The FMA exception"). Any other object with FMA still fails.
# It also fails when such an object has a static initializer (_GLOBAL__sub_I_*) holding a VEX or
# EVEX instruction: that code runs when the library loads, on any CPU, before the ISA is chosen
# (a header table initialized by a function call, included by an ISA file, does it).
#
# Usage: check_isa_objects.sh OBJECT...   (the objects of the build's libraries and tests; those
# not named *_avx2.cpp.o or *_avx512.cpp.o are ignored). Exit 0: none found; 1: found (listed);
# 77: objdump missing (ctest reports the test as skipped).
set -uo pipefail
if ! command -v objdump >/dev/null; then
  echo "check_isa_objects.sh: objdump not found (binutils): skipped"
  exit 77
fi
checked=0
bad=0
for obj in "$@"; do
  case $obj in
    *_avx2.cpp.o | *_avx512.cpp.o) ;;
    *) continue ;;
  esac
  if [[ ! -f $obj ]]; then
    echo "check_isa_objects.sh: $obj: not built"
    bad=1
    continue
  fi
  checked=$((checked + 1))
  fma_allowed=0
  case $obj in
    */nsm_conv_avx2.cpp.o | */nsm_conv_avx512.cpp.o) fma_allowed=1 ;;
  esac
  hits=$(objdump -d --no-show-raw-insn "$obj" | grep -E '\bv(fmadd|fmsub|fnmadd|fnmsub)[0-9a-z]*\b')
  if [[ -n $hits && $fma_allowed == 0 ]]; then
    echo "$obj: $(wc -l <<<"$hits") fused multiply-add instruction(s), e.g.:"
    head -3 <<<"$hits"
    bad=1
  fi
  init=$(objdump -d --no-show-raw-insn "$obj" |
    awk '/^[0-9a-f]+ <_GLOBAL__sub_I/ { p = 1; next } /^$/ { p = 0 } p' | grep -E $'\tv[a-z0-9]+ ')
  if [[ -n $init ]]; then
    echo "$obj: a static initializer holds $(wc -l <<<"$init") vector instruction(s), e.g.:"
    head -3 <<<"$init"
    bad=1
  fi
done
if ((checked == 0)); then
  echo "check_isa_objects.sh: no *_avx2.cpp.o or *_avx512.cpp.o among the objects given"
  exit 1
fi
echo "$checked ISA objects checked"
exit $bad
