#pragma once
// Run-time choice of the SIMD paths. Every SIMD path in shadowlab has a scalar oracle that
// gives the same bits; SHADOWLAB_SCALAR=1 forces the oracles (tests compare both).

namespace shadowlab {

// True when this CPU runs AVX2 code.
bool cpu_has_avx2();
// True when the AVX2 paths should be used: the CPU has AVX2 and SHADOWLAB_SCALAR is not "1".
bool use_avx2_paths();
// True when this CPU runs the AVX-512 kernels (AVX-512 F, VL and DQ).
bool cpu_has_avx512();
// True when the AVX-512 kernels should be used: the CPU has them, the AVX2 paths are on, and
// SHADOWLAB_ISA is not "avx2" (which keeps the narrower kernels, so that both are measured and
// tested on one machine).
bool use_avx512_paths();

}  // namespace shadowlab
