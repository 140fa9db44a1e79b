#pragma once
// The target attribute of a hand-written SIMD kernel: SL_TARGET("avx2") compiles the function
// for AVX2 (and SL_TARGET("avx512f,avx512dq") for AVX-512) inside a baseline x86-64 build; the
// run-time choice of which kernel runs is core/isa.h's.
//
// In the emulated build (SHADOWLAB_EMULATE_SIMD, docs/testing.md, "Testing the AVX-512
// kernels on any machine") the attribute is empty and core/simd_emulation.h maps the AVX2 and AVX-512
// intrinsics to SIMDe's portable code, so the kernels run, and are compared with their scalar
// oracles, on a CPU without those extensions. Without the attribute the compiler cannot emit
// an instruction this CPU lacks.
#ifdef SHADOWLAB_EMULATE_SIMD
#define SL_TARGET(isa)
#else
#define SL_TARGET(isa) __attribute__((target(isa)))
#endif
