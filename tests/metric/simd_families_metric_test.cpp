// Which instruction set the SIMD kernel family of metric/ runs in this process (docs/simd.md),
// in every build, the sanitizer and fuzz builds included (tests/core/simd_families_core_test.cpp
// says why); tests/metric/flip_kernels_test.cpp compares every table with the scalar one.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/isa.h"
#include "metric/flip_kernels.h"

namespace shadowlab {
namespace {

TEST(SimdFamilies, MetricFamiliesRunTheProcessesInstructionSet) {
  const Isa isa = process_isa();
  const Isa flip = flip_kernels(isa).isa;
  std::printf("process %s: flip %s\n", isa_name(isa), isa_name(flip));
  EXPECT_EQ(flip, isa);
  EXPECT_EQ(flip_kernels(isa).power != nullptr, isa != Isa::scalar);
}

}  // namespace
}  // namespace shadowlab
