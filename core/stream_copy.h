#pragma once
// Copies of float rows into memory that is written far more than the caches hold (a filtered
// moment map: 16 bytes per texel for MSM, ~35 MB on the default scene's cube): the whole 64-byte
// lines of the destination are written with non-temporal stores, which do not first read the
// line from memory as an ordinary store does (docs/techniques/pipeline.md gives the
// measurement). The values are a copy's: every table gives the same bits as the scalar one
// (tests/core/stream_copy_test.cpp). Non-temporal stores are weakly ordered: a thread calls
// stream_fence() after its copies and before it signals that its work is done (a fence per
// copy, i.e. per row, made the MSM filter ~30 % slower than without).
#include <cstddef>

#include "core/isa.h"

namespace shadowlab {

// dst[i] = src[i] for i < n; the ranges do not overlap.
using StreamCopy = void (*)(const float* src, size_t n, float* dst);

// The family's table per instruction set (docs/simd.md): the scalar copy (memcpy) is the
// oracle; the AVX2 and AVX-512 copies (one body, core/stream_copy_simd.inl) stream whole lines.
struct StreamCopyKernels {
  Isa isa;  // the instruction set the copy was compiled for
  StreamCopy copy;
};
const StreamCopyKernels& stream_copy_kernels(Isa isa);

// The copy of process_isa()'s table.
StreamCopy stream_copy_kernel();

// Orders this thread's earlier stream copies before its later stores (x86 sfence).
void stream_fence();

}  // namespace shadowlab
