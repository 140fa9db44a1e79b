// Which instruction set each SIMD kernel family of core/ runs in this process (docs/simd.md).
// Every build runs this, the sanitizer and fuzz builds (clang) included: the ISA files are
// compiled with their own flags (cmake/isa_sources.cmake), so there too an AVX-512 machine runs
// the AVX-512 tables; the families' own tests compare every table with the scalar one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/block_bounds.h"
#include "core/isa.h"
#include "core/stream_copy.h"

namespace shadowlab {
namespace {

TEST(SimdFamilies, CoreFamiliesRunTheProcessesInstructionSet) {
  const Isa isa = process_isa();
  const Isa copy = stream_copy_kernels(isa).isa;
  const Isa bounds = block_bounds_kernels(isa).isa;
  std::printf("process %s: stream_copy %s, block_bounds %s\n", isa_name(isa), isa_name(copy),
              isa_name(bounds));
  EXPECT_EQ(copy, isa);
  // The block bounds' widest table is AVX2's (a 16-pixel segment is six AVX2 vectors).
  EXPECT_EQ(bounds, std::min(isa, Isa::avx2));
  EXPECT_EQ(block_bounds_kernels(Isa::scalar).add_full_segment, nullptr);
  if (isa != Isa::scalar) {
    EXPECT_NE(block_bounds_kernels(isa).add_full_segment, nullptr);
  }
  // The process's copy is its table's.
  EXPECT_EQ(stream_copy_kernel(), stream_copy_kernels(isa).copy);
}

}  // namespace
}  // namespace shadowlab
