// The moment filters' row kernels (techniques/filters/moments_common/moment_rows.h): every entry of every table this CPU
// has against the scalar table, byte for byte, on rows whose lengths leave heads and tails for
// 8- and 16-lane steps, with empty texels (+inf), NaN, values past the far plane and ties, and
// output rows at every 16-byte offset within a cache line. The fused rows (no scalar entry)
// against the scalar rows they stand for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/isa.h"
#include "techniques/filters/moments_common/moment_rows.h"

namespace shadowlab {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Distances as the filters see them: uniform in [0, 1.2] (> 1: nothing seen), runs of one
// value, +inf and NaN.
std::vector<float> distances(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.2f);
  std::vector<float> d(size_t(n) + 16);
  for (float& v : d) v = u(rng);
  for (size_t i = 0; i < d.size(); i += 11) d[i] = std::numeric_limits<float>::infinity();
  for (size_t i = 5; i < d.size(); i += 13) d[i] = std::numeric_limits<float>::quiet_NaN();
  for (size_t i = 2; i < d.size() && i < 10; ++i) d[i] = 0.7f;
  return d;
}

// `count` rows of n positive values in planes of count/4 rows, and their pointer tables. The first
// 12 texels are flat: 0.7 in the even planes, 0.49 = 0.7² in the odd ones, so that VSM's b − a²
// rounds to tiny values of either sign (the positive part).
struct Rows {
  std::vector<std::vector<double>> d;
  std::vector<std::vector<float>> f;
  std::vector<const double*> dp;
  std::vector<const float*> fp;
};
Rows window_rows(int count, int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Rows r;
  r.d.resize(size_t(count));
  r.f.resize(size_t(count));
  for (int j = 0; j < count; ++j) {
    for (int x = 0; x < n; ++x) {
      const bool odd_plane = (j / std::max(1, count / 4)) % 2 == 1;
      const double v = x >= 12 ? u(rng) : odd_plane ? 0.49 : 0.7;
      r.d[size_t(j)].push_back(v);
      r.f[size_t(j)].push_back(float(v));
    }
    r.dp.push_back(r.d[size_t(j)].data());
    r.fp.push_back(r.f[size_t(j)].data());
  }
  return r;
}

constexpr int kWidths[kMomentWidths] = {1, 3, 5, 7, 9};
constexpr int kLengths[] = {1, 7, 15, 16, 17, 33, 67};

TEST(MomentRows, EveryTablesPlainRowsGiveTheScalarBits) {
  const MomentRowKernels& s = moment_row_kernels(Isa::scalar);
  for (const Isa isa : cpu_isas()) {
    const MomentRowKernels& t = moment_row_kernels(isa);
    ASSERT_EQ(t.isa, isa);
    for (const int n : kLengths) {
      SCOPED_TRACE(testing::Message() << isa_name(isa) << " n " << n);
      const std::vector<float> d = distances(n, uint32_t(n));
      auto both = [&](auto&& run, auto& a, auto& b) {
        run(s, a);
        run(t, b);
        EXPECT_TRUE(same_bytes(a, b));
      };
      std::vector<float> fa, fb;
      std::vector<double> da, db;
      both([&](const MomentRowKernels& k, std::vector<float>& o) {
        o.assign(size_t(n), -1.0f);
        k.finite_row(d.data(), n, o.data());
      }, fa, fb);
      both([&](const MomentRowKernels& k, std::vector<double>& o) {
        o.assign(2 * size_t(n), -1.0);
        k.moment_row(d.data(), n, o.data(), o.data() + n);
      }, da, db);
      for (const double sign : {1.0, -1.0}) {
        both([&](const MomentRowKernels& k, std::vector<double>& o) {
          o.assign(2 * size_t(n), -1.0);
          k.warped_row(d.data(), n, 40.0, sign, o.data(), o.data() + n);
        }, da, db);
        both([&](const MomentRowKernels& k, std::vector<float>& o) {
          o.assign(size_t(n), -1.0f);
          k.warp_row_f(d.data(), n, 40.0, sign, o.data());
        }, fa, fb);
      }
      both([&](const MomentRowKernels& k, std::vector<double>& o) {
        o.assign(size_t(n), -1.0);
        k.esm_exp_row(d.data(), n, 300.0, 0.05, o.data());
      }, da, db);
      std::vector<double> filtered(static_cast<size_t>(n));
      for (int x = 0; x < n; ++x)
        filtered[size_t(x)] = 1e-3 + (d[size_t(x) + 1] > 0.5f ? 2.5e5 : 0.3);
      both([&](const MomentRowKernels& k, std::vector<float>& o) {
        o.assign(size_t(n), -1.0f);
        k.esm_log_row(filtered.data(), n, 300.0, 0.05, o.data());
      }, fa, fb);
      EXPECT_EQ(s.row_min_dist(d.data() + 1, n), t.row_min_dist(d.data() + 1, n));
      both([&](const MomentRowKernels& k, std::vector<float>& o) {
        o.assign(4 * size_t(n), -1.0f);
        k.power_row(d.data(), n, size_t(n), o.data());
      }, fa, fb);
      // The variance's positive part: m2 < m1² in some texels.
      std::vector<double> m1(static_cast<size_t>(n)), m2(static_cast<size_t>(n));
      for (int x = 0; x < n; ++x) {
        m1[size_t(x)] = double(d[size_t(x)] < 1.0f ? d[size_t(x)] : 1.0f);
        m2[size_t(x)] = m1[size_t(x)] * m1[size_t(x)] + (x % 3 == 0 ? -1e-9 : 1e-9);
      }
      both([&](const MomentRowKernels& k, std::vector<float>& o) {
        o.assign(2 * size_t(n), -1.0f);
        k.mean_variance_row(m1.data(), m2.data(), n, o.data(), o.data() + n);
      }, fa, fb);
      // Interleaves and the 16-bit store into rows at every 16-byte offset of a line.
      alignas(64) static float out_a[4 * 80 + 64], out_b[4 * 80 + 64];
      for (int off = 0; off < 16; off += 4) {
        std::vector<float> src(4 * size_t(n));
        for (size_t i = 0; i < src.size(); ++i) src[i] = d[i % d.size()] * 0.8f;
        for (const int which : {2, 4}) {
          std::memset(out_a, 0, sizeof out_a);
          std::memset(out_b, 0, sizeof out_b);
          if (which == 2) {
            s.interleave_row(src.data(), src.data() + n, n, out_a + off);
            t.interleave_row(src.data(), src.data() + n, n, out_b + off);
          } else {
            s.interleave4_row(src.data(), n, out_a + off);
            t.interleave4_row(src.data(), n, out_b + off);
          }
          EXPECT_EQ(std::memcmp(out_a, out_b, sizeof out_a), 0) << which << " at +" << off;
        }
        std::memcpy(out_a + off, src.data(), src.size() * 4);
        std::memcpy(out_b + off, src.data(), src.size() * 4);
        s.quantize16(size_t(n), out_a + off);
        t.quantize16(size_t(n), out_b + off);
        EXPECT_EQ(std::memcmp(out_a, out_b, sizeof out_a), 0) << "quantize16 at +" << off;
      }
      // The runtime-width rows.
      for (const int k : {1, 2, 5, 11}) {
        std::vector<double> ext(size_t(n + k));
        std::vector<float> extf(size_t(n + k));
        for (size_t i = 0; i < ext.size(); ++i) {
          extf[i] = d[i % d.size()] < 1.0f ? d[i % d.size()] : 1.0f;
          ext[i] = double(extf[i]) * 3.0;
        }
        both([&](const MomentRowKernels& kk, std::vector<double>& o) {
          o.assign(size_t(n), -1.0);
          kk.hsum_row_d(ext.data(), n, k, o.data());
        }, da, db);
        both([&](const MomentRowKernels& kk, std::vector<float>& o) {
          o.assign(size_t(n), -1.0f);
          kk.hsum_row_f(extf.data(), n, k, o.data());
        }, fa, fb);
        const Rows r = window_rows(k, n, uint32_t(k));
        both([&](const MomentRowKernels& kk, std::vector<double>& o) {
          o.assign(size_t(n), -1.0);
          kk.vsum_rows_d(r.dp.data(), n, k, 1.0 / double(k * k), o.data());
        }, da, db);
        both([&](const MomentRowKernels& kk, std::vector<float>& o) {
          o.assign(size_t(n), -1.0f);
          kk.vsum_rows_f(r.fp.data(), n, k, 1.0f / float(k * k), o.data());
        }, fa, fb);
      }
    }
  }
}

TEST(MomentRows, EveryTablesFixedWidthRowsGiveTheScalarBits) {
  const MomentRowKernels& s = moment_row_kernels(Isa::scalar);
  for (const Isa isa : cpu_isas()) {
    const MomentRowKernels& t = moment_row_kernels(isa);
    for (int slot = 0; slot < kMomentWidths; ++slot) {
      const int K = kWidths[slot];
      ASSERT_EQ(moment_width_slot(K), slot);
      for (const int n : kLengths) {
        SCOPED_TRACE(testing::Message() << isa_name(isa) << " K " << K << " n " << n);
        const std::vector<float> d = distances(n + K, uint32_t(n * K));
        std::vector<float> ext(size_t(n + K));
        for (size_t i = 0; i < ext.size(); ++i) ext[i] = d[i] < 1.0f ? d[i] : 1.0f;
        std::vector<double> extd(ext.begin(), ext.end());
        std::vector<double> da(2 * size_t(n), -1.0), db = da;
        s.hsum_k[slot](extd.data(), n, da.data());
        t.hsum_k[slot](extd.data(), n, db.data());
        EXPECT_TRUE(same_bytes(da, db));
        s.hsum_moments_k[slot](ext.data(), n, da.data(), da.data() + n);
        t.hsum_moments_k[slot](ext.data(), n, db.data(), db.data() + n);
        EXPECT_TRUE(same_bytes(da, db));
        std::vector<float> fa(4 * size_t(n), -1.0f), fb = fa;
        s.hsum_powers_k[slot](ext.data(), n, fa.data(), fa.data() + n, fa.data() + 2 * n,
                              fa.data() + 3 * n);
        t.hsum_powers_k[slot](ext.data(), n, fb.data(), fb.data() + n, fb.data() + 2 * n,
                              fb.data() + 3 * n);
        EXPECT_TRUE(same_bytes(fa, fb));
        const Rows r = window_rows(4 * K, n, uint32_t(K + n));
        const double inv = 1.0 / double(K * K);
        const float finv = 1.0f / float(K * K);
        s.vsm_out_k[slot](r.dp.data(), n, inv, fa.data(), fa.data() + n);
        t.vsm_out_k[slot](r.dp.data(), n, inv, fb.data(), fb.data() + n);
        EXPECT_TRUE(same_bytes(fa, fb));
        s.mean_out_k[slot](r.fp.data(), n, finv, fa.data());
        t.mean_out_k[slot](r.fp.data(), n, finv, fb.data());
        EXPECT_TRUE(same_bytes(fa, fb));
        // ESM's windows: sums of exponentials up to e^300.
        std::vector<std::vector<double>> e(static_cast<size_t>(K));
        std::vector<const double*> ep;
        for (int j = 0; j < K; ++j) {
          for (int x = 0; x < n; ++x)
            e[size_t(j)].push_back(1.0 + r.d[size_t(j)][size_t(x)] * 1e130);
          ep.push_back(e[size_t(j)].data());
        }
        s.esm_out_k[slot](ep.data(), n, inv, 300.0, 0.05, fa.data());
        t.esm_out_k[slot](ep.data(), n, inv, 300.0, 0.05, fb.data());
        EXPECT_TRUE(same_bytes(fa, fb));

        if (isa == Isa::scalar) {
          EXPECT_EQ(t.vsm_out_interleaved[slot], nullptr);
          EXPECT_EQ(t.msm_out_interleaved[slot], nullptr);
          EXPECT_EQ(t.msm_hsum_out[slot], nullptr);
          continue;
        }
        // The fused rows against the scalar rows they stand for, into rows at every 16-byte
        // offset of a line (the maps' storage is 16-byte aligned).
        alignas(64) static float want[4 * 80 + 64], got[4 * 80 + 64];
        std::vector<float> planes(4 * static_cast<size_t>(n));
        for (int off = 0; off < 16; off += 4) {
          std::memset(want, 0, sizeof want);
          std::memset(got, 0, sizeof got);
          s.vsm_out_k[slot](r.dp.data(), n, inv, planes.data(), planes.data() + n);
          s.interleave_row(planes.data(), planes.data() + n, n, want + off);
          t.vsm_out_interleaved[slot](r.dp.data(), n, inv, got + off);
          EXPECT_EQ(std::memcmp(want, got, sizeof want), 0) << "vsm at +" << off;

          std::memset(want, 0, sizeof want);
          std::memset(got, 0, sizeof got);
          for (int c = 0; c < 4; ++c)
            s.mean_out_k[slot](r.fp.data() + c * K, n, finv, planes.data() + c * n);
          s.interleave4_row(planes.data(), n, want + off);
          t.msm_out_interleaved[slot](r.fp.data(), n, finv, got + off);
          EXPECT_EQ(std::memcmp(want, got, sizeof want), 0) << "msm at +" << off;

          // The new bottom row's sums go into h[c], which is the window's last row of plane c.
          Rows wa = window_rows(4 * K, n, uint32_t(K + n)), wb = wa;
          auto run = [&](const MomentRowKernels& k, Rows& w, float* out) {
            float* h[4];
            for (int c = 0; c < 4; ++c) h[c] = w.f[size_t(c * K + K - 1)].data();
            if (k.msm_hsum_out[slot]) {
              k.msm_hsum_out[slot](ext.data(), h, w.fp.data(), n, finv, out);
              return;
            }
            k.hsum_powers_k[slot](ext.data(), n, h[0], h[1], h[2], h[3]);
            for (int c = 0; c < 4; ++c)
              k.mean_out_k[slot](w.fp.data() + c * K, n, finv, planes.data() + c * n);
            k.interleave4_row(planes.data(), n, out);
          };
          std::memset(want, 0, sizeof want);
          std::memset(got, 0, sizeof got);
          run(s, wa, want + off);
          run(t, wb, got + off);
          EXPECT_EQ(std::memcmp(want, got, sizeof want), 0) << "msm hsum at +" << off;
          for (int c = 0; c < 4; ++c)
            EXPECT_TRUE(same_bytes(wa.f[size_t(c * K + K - 1)], wb.f[size_t(c * K + K - 1)]));
        }
      }
    }
  }
}

}  // namespace
}  // namespace shadowlab
