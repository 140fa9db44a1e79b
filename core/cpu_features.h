#pragma once
// Run-time choice of the SIMD paths. Every SIMD path in shadowlab has a scalar oracle that
// gives the same bits; SHADOWLAB_SCALAR=1 forces the oracles (tests compare both).

namespace shadowlab {

// True when this CPU runs AVX2 code.
bool cpu_has_avx2();
// True when the AVX2 paths should be used: the CPU has AVX2 and SHADOWLAB_SCALAR is not "1".
bool use_avx2_paths();

}  // namespace shadowlab
