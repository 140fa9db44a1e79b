// Which instruction set each SIMD kernel family runs in this process (docs/simd.md), and that the
// vector tables execute and give the scalar table's bits. Every build runs this, the sanitizer
// and fuzz builds (clang) included: the vector files are compiled with their own target flags
// (cmake/isa_sources.cmake), so there too an AVX-512 machine runs the AVX-512 tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "core/isa.h"
#include "techniques/filters/moments_common/centred_window3.h"
#include "techniques/filters/esm/esm_tile_rows.h"
#include "techniques/pipeline/face_rows.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/filters/moments_common/moment_rows.h"
#include "techniques/nsm/nsm_conv.h"
#include "techniques/rt/atrous.h"

namespace shadowlab {
namespace {

TEST(SimdFamilies, EachFamilyRunsTheProcessesInstructionSet) {
  const Isa isa = process_isa();
  const Isa window = centred_window3_kernels(isa).isa;
  const Isa rows = face_row_kernels(isa).isa;
  const Isa lookup = lookup_kernels(isa).isa;
  const Isa moments = moment_row_kernels(isa).isa;
  const Isa esm_tiles = esm_tile_kernels(isa).isa;
  const Isa batches = lookup_batch_kernels(isa).isa;
  const Isa nsm_conv = nsm_conv_kernels(isa).isa;
  const Isa atrous = atrous_kernels(isa).isa;
  std::printf(
      "process %s: centred_window3 %s, face_rows %s, lookup %s, moment_rows %s, esm_tiles %s, "
      "lookup_batches %s, nsm_conv %s, atrous %s\n",
      isa_name(isa), isa_name(window), isa_name(rows), isa_name(lookup), isa_name(moments),
      isa_name(esm_tiles), isa_name(batches), isa_name(nsm_conv), isa_name(atrous));
  // The window, face row and moment row families have a table per set; the lookup's widest is
  // AVX2.
  EXPECT_EQ(window, isa);
  EXPECT_EQ(rows, isa);
  EXPECT_EQ(moments, isa);
  EXPECT_EQ(esm_tiles, isa);
  EXPECT_EQ(batches, isa);
  EXPECT_EQ(nsm_conv, isa);
  EXPECT_EQ(atrous, isa);
  EXPECT_EQ(nsm_conv_kernels(Isa::scalar).isa, Isa::scalar);
  EXPECT_EQ(lookup, std::min(isa, Isa::avx2));
  // The scalar tables: the window's row, the lookup's merge and no batch kernels.
  EXPECT_EQ(centred_window3_kernels(Isa::scalar).isa, Isa::scalar);
  EXPECT_EQ(lookup_kernels(Isa::scalar).receivers8, nullptr);
  EXPECT_NE(lookup_kernels(Isa::scalar).merge8, nullptr);
  EXPECT_EQ(moment_row_kernels(Isa::scalar).msm_hsum_out[0], nullptr);
  EXPECT_EQ(esm_tile_kernels(Isa::scalar).box_tile, nullptr);
  EXPECT_EQ(lookup_batch_kernels(Isa::scalar).vsm_batch, nullptr);
  if (isa != Isa::scalar) {
    EXPECT_NE(lookup_kernels(isa).receivers8, nullptr);
    EXPECT_NE(moment_row_kernels(isa).msm_hsum_out[0], nullptr);
    EXPECT_NE(esm_tile_kernels(isa).box_tile, nullptr);
    EXPECT_NE(lookup_batch_kernels(isa).vsm_batch, nullptr);
    // MSM's reconstruction runs in 8 lanes exactly with the AVX-512 table.
    EXPECT_EQ(lookup_batch_kernels(isa).msm_taps1 != nullptr, isa == Isa::avx512);
  }
}

// The widest table this CPU has, run on windows whose means and variances round differently in
// every lane, against the scalar table: the vector code executed, with the oracle's bits.
TEST(SimdFamilies, TheWidestWindowRowExecutesWithTheScalarBits) {
  const Isa widest = cpu_isa();
  if (widest == Isa::scalar) GTEST_SKIP() << "no vector set on this CPU";
  const int n = 67;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> r[3];
  for (auto& row : r) {
    row.resize(size_t(n) + 2);
    for (float& v : row) v = u(rng);
  }
  std::vector<float> want(2 * size_t(n), -1.0f), got(2 * size_t(n), -1.0f);
  centred_window3_kernels(Isa::scalar)
      .row(r[0].data(), r[1].data(), r[2].data(), n, want.data(), want.data() + n, 1);
  centred_window3_kernels(widest)
      .row(r[0].data(), r[1].data(), r[2].data(), n, got.data(), got.data() + n, 1);
  EXPECT_EQ(std::memcmp(want.data(), got.data(), want.size() * sizeof(float)), 0)
      << isa_name(widest);
}

// The same for the face rows: every table this CPU has, the radial tile with its minimum and the
// paraboloid row with its minimum, on rows of 1/w whose lengths leave vector tails.
TEST(SimdFamilies, EveryFaceRowTableGivesTheScalarBits) {
  const int w = 37, h = 5;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.05f, 3.0f);
  std::vector<float> input(size_t(w * h));
  for (float& v : input) v = u(rng);
  input[7] = 0.0f;  // an empty texel: +inf
  auto run = [&](Isa isa, std::vector<float>& out, float mins[2]) {
    out = input;
    const FaceRowKernels& k = face_row_kernels(isa);
    mins[0] = k.radial_tile_min(out.data(), size_t(w), 1, w, 0, h - 1, -0.9f, 0.05f, 0.8f, 0.07f,
                                0.125f);
    mins[1] = k.paraboloid_row_min(out.data() + size_t(w) * size_t(h - 1), 2, w, 0.125f);
  };
  std::vector<float> want, got;
  float want_min[2], got_min[2];
  run(Isa::scalar, want, want_min);
  for (const Isa isa : cpu_isas()) {
    run(isa, got, got_min);
    EXPECT_EQ(std::memcmp(want.data(), got.data(), want.size() * sizeof(float)), 0)
        << isa_name(isa);
    EXPECT_EQ(std::memcmp(want_min, got_min, sizeof want_min), 0) << isa_name(isa);
  }
}

}  // namespace
}  // namespace shadowlab
