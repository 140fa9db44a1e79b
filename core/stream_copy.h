#pragma once
// Copies of float rows into memory that is written far more than the caches hold (a filtered
// moment map: 16 bytes per texel for MSM, ~35 MB on the default scene's cube): the whole 64-byte
// lines of the destination are written with non-temporal stores, which do not first read the
// line from memory as an ordinary store does (docs/techniques/pipeline.md gives the
// measurement). The values are a copy's: every path gives the same bits as the scalar one
// (tests/core/stream_copy_test.cpp). Non-temporal stores are weakly ordered: a thread calls
// stream_fence() after its copies and before it signals that its work is done (a fence per
// copy, i.e. per row, made the MSM filter ~30 % slower than without).
#include <cstddef>

namespace shadowlab {

// dst[i] = src[i] for i < n; the ranges do not overlap.
using StreamCopy = void (*)(const float* src, size_t n, float* dst);

// The copy for this run: AVX-512 or AVX2 stores per core/isa.h's process_isa(), else the scalar loop.
StreamCopy stream_copy_kernel();

// Orders this thread's earlier stream copies before its later stores (x86 sfence).
void stream_fence();

// The scalar loop (the oracle) and the SIMD paths, for the tests; the AVX ones need their ISA.
void stream_copy_scalar(const float* src, size_t n, float* dst);
void stream_copy_avx2(const float* src, size_t n, float* dst);
void stream_copy_avx512(const float* src, size_t n, float* dst);

}  // namespace shadowlab
