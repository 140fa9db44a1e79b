// Which instruction set each SIMD kernel family of raster/ runs in this process (docs/simd.md),
// in every build, the sanitizer and fuzz builds included (tests/core/simd_families_core_test.cpp
// says why); the families' own tests compare every table with the scalar one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/isa.h"
#include "raster/depth_kernels.h"
#include "raster/gbuffer_resolve_simd.h"
#include "raster/setup_simd.h"
#include "raster/vertex_transform.h"

namespace shadowlab {
namespace {

TEST(SimdFamilies, RasterFamiliesRunTheProcessesInstructionSet) {
  const Isa isa = process_isa();
  const Isa depth = depth_kernels(isa).isa;
  const Isa setup = setup_kernels(isa).isa;
  const Isa transform = vertex_transform_kernels(isa).isa;
  const Isa resolve = gbuffer_resolve_kernels(isa).isa;
  std::printf("process %s: depth %s, setup %s, vertex_transform %s, gbuffer_resolve %s\n",
              isa_name(isa), isa_name(depth), isa_name(setup), isa_name(transform),
              isa_name(resolve));
  EXPECT_EQ(depth, isa);
  EXPECT_EQ(setup, isa);
  EXPECT_EQ(resolve, isa);
  // The vertex transform's widest table is AVX2's.
  EXPECT_EQ(transform, std::min(isa, Isa::avx2));
  EXPECT_STREQ(depth_kernel_name(), isa_name(isa));
  // The AVX-512 forms exist only in the AVX-512 tables; the scalar tables leave the batch and
  // resolve kernels to their callers' own loops.
  EXPECT_EQ(depth_kernels(isa).triangle != nullptr, isa == Isa::avx512);
  EXPECT_EQ(gbuffer_resolve_kernels(isa).lanes16 != nullptr, isa == Isa::avx512);
  EXPECT_EQ(setup_kernels(isa).batch8 != nullptr, isa != Isa::scalar);
  EXPECT_EQ(gbuffer_resolve_kernels(isa).run8 != nullptr, isa != Isa::scalar);
}

}  // namespace
}  // namespace shadowlab
