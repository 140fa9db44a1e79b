// MSM's filter (techniques/filters/moments_common/moment_filter.h): the four power moments d, d², d³, d⁴ box-filtered
// in float, and the AVX-512 and AVX2 writers of the interleaved map's 64-byte lines.
#include "techniques/filters/moments_common/moment_filter.h"

#include "techniques/filters/moments_common/moment_box.h"

namespace shadowlab {
namespace {

// MSM's power moments of one row, in float (moment_filter.h says why): p[0..3][x] = d, d²,
// d³ = d²·d, d⁴ = d²·d² (d = finite_dist), each plane at its own offset `stride` from the last.
SL_ROW_CLONES void power_row(const float* row, int w, size_t stride, float* p) {
  for (int x = 0; x < w; ++x) p[x] = finite_dist_bits(row[x]);
  for (int x = 0; x < w; ++x) {
    const float d = p[x], d2 = d * d;
    p[stride + size_t(x)] = d2;
    p[2 * stride + size_t(x)] = d2 * d;
    p[3 * stride + size_t(x)] = d2 * d2;
  }
}

// out[4x + c] = rows[c·w + x] for c = 0..3: four rows into one interleaved row.
SL_ROW_CLONES void interleave4_row(const float* rows, int w, float* out) {
  const int head = texels_to_line(out, 4, w);
  for (int x = 0; x < head; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
  for (int x = head; x < w; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
}

// One texel of hsum_powers_k: the four sums at x (also the fused AVX2 row's heads and tails).
template <int K>
inline void hsum_powers_texel(const float* ext, int x, float* const* h) {
  float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
  for (int i = 0; i < K; ++i) {
    const float d = ext[x + i], d2 = d * d;
    s0 += d;
    s1 += d2;
    s2 += d2 * d;
    s3 += d2 * d2;
  }
  h[0][x] = s0;
  h[1][x] = s1;
  h[2][x] = s2;
  h[3][x] = s3;
}

// MSM: h_c[x] = Σ_i d^(c+1) over ext[x .. x + K − 1] (ext: the clamped finite row), the powers
// formed as power_row forms them (d² = d·d, d³ = d²·d, d⁴ = d²·d²) and each sum started from 0
// and added in i order: hsum_k's sums of power_row's planes, without writing the planes.
template <int K>
SL_ROW_CLONES void hsum_powers_k(const float* ext, int w, float* h0, float* h1, float* h2,
                                 float* h3) {
  float* const h[4] = {h0, h1, h2, h3};
  for (int x = 0; x < w; ++x) hsum_powers_texel<K>(ext, x, h);
}

// MSM: one plane's K rows summed in float, × inv.
template <int K>
SL_ROW_CLONES void mean_out_k(const float* const* rows, int w, float inv, float* out) {
  const float* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  for (int x = 0; x < w; ++x) {
    float a = r[0][x];
    for (int j = 1; j < K; ++j) a += r[j][x];
    out[x] = a * inv;
  }
}

#if defined(__x86_64__)
// One texel of the fused MSM output rows, for their heads and tails (the vector steps'
// operations): the four means from plane c's rows[c·K .. c·K + K − 1], summed in float.
template <int K>
inline void msm_out_texel(const float* const* rows, int x, float inv, float* out) {
  for (int c = 0; c < 4; ++c) {
    float a = rows[c * K][x];
    for (int j = 1; j < K; ++j) a += rows[c * K + j][x];
    out[4 * x + c] = a * inv;
  }
}

// Four planes' 16 texels (m[c]: plane c, texels x .. x + 15) transposed to (m1 m2 m3 m4) per
// texel: line[q] holds texels 4q .. 4q + 3, the q-th 64 bytes of the interleaved row.
SL_TARGET("avx512f") inline void transpose4_avx512(const __m512* m, __m512* line) {
  // Within each 128-bit lane (texels 4q .. 4q + 3): t0, t1 planes 0 1 interleaved, t2, t3
  // planes 2 3; u_i texel 4q + i's four moments in lane q.
  // (The zero-masked forms with every lane on: GCC 12's unmasked ones trip
  // -Wmaybe-uninitialized, as in core/exp_log.h.)
  const __m512 t0 = _mm512_maskz_unpacklo_ps(0xFFFF, m[0], m[1]);
  const __m512 t1 = _mm512_maskz_unpackhi_ps(0xFFFF, m[0], m[1]);
  const __m512 t2 = _mm512_maskz_unpacklo_ps(0xFFFF, m[2], m[3]);
  const __m512 t3 = _mm512_maskz_unpackhi_ps(0xFFFF, m[2], m[3]);
  const __m512 u0 = _mm512_maskz_shuffle_ps(0xFFFF, t0, t2, 0x44);
  const __m512 u1 = _mm512_maskz_shuffle_ps(0xFFFF, t0, t2, 0xEE);
  const __m512 u2 = _mm512_maskz_shuffle_ps(0xFFFF, t1, t3, 0x44);
  const __m512 u3 = _mm512_maskz_shuffle_ps(0xFFFF, t1, t3, 0xEE);
  // Lanes regrouped: v0 = texels 0 4 1 5, v1 = 2 6 3 7, v2 = 8 12 9 13, v3 = 10 14 11 15.
  const __m512 v0 = _mm512_maskz_shuffle_f32x4(0xFFFF, u0, u1, 0x44);
  const __m512 v1 = _mm512_maskz_shuffle_f32x4(0xFFFF, u2, u3, 0x44);
  const __m512 v2 = _mm512_maskz_shuffle_f32x4(0xFFFF, u0, u1, 0xEE);
  const __m512 v3 = _mm512_maskz_shuffle_f32x4(0xFFFF, u2, u3, 0xEE);
  line[0] = _mm512_maskz_shuffle_f32x4(0xFFFF, v0, v1, 0x88);  // texels 0–3
  line[1] = _mm512_maskz_shuffle_f32x4(0xFFFF, v0, v1, 0xDD);  // 4–7
  line[2] = _mm512_maskz_shuffle_f32x4(0xFFFF, v2, v3, 0x88);  // 8–11
  line[3] = _mm512_maskz_shuffle_f32x4(0xFFFF, v2, v3, 0xDD);  // 12–15
}

// The transposed 16 texels written as four 64-byte lines at out (64-byte aligned) with
// non-temporal stores.
SL_TARGET("avx512f") inline void stream_transposed4_avx512(const __m512* m, float* out) {
  __m512 line[4];
  transpose4_avx512(m, line);
  for (int q = 0; q < 4; ++q) _mm512_stream_ps(out + 16 * q, line[q]);
}

// MSM's four planes' output row straight into the interleaved map: mean_out_k's float sums and
// products for planes c = 0..3 (rows[c·K .. c·K + K − 1]), 16 texels at a time, transposed to
// (m1 m2 m3 m4) per texel and written as four 64-byte lines with non-temporal stores (as
// core/stream_copy.h writes them; the caller's fused_box fences). What mean_out_k,
// interleave4_row and the stream copy do in three passes over tmp rows, in one; the same bits
// (tests: MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoopsBitForBit). Texels before the
// first 64-byte line and after the last whole 16 go one by one in the same operations.
template <int K>
SL_TARGET("avx512f") void msm_out_interleaved_avx512(const float* const* rows,
                                                     int w, float inv,
                                                     float* out) {
  // Non-temporal stores need aligned addresses: a row that cannot reach a line on a texel
  // boundary (never for the map's 16-byte aligned storage) goes one texel at a time.
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) msm_out_texel<K>(rows, x, inv, out);
  // The row pointers in locals: through `rows` they would be reloaded after every store.
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m512 vinv = _mm512_set1_ps(inv);
  for (; x + 16 <= w; x += 16) {
    __m512 m[4];
    for (int c = 0; c < 4; ++c) {
      __m512 a = _mm512_loadu_ps(r[c * K] + x);
      for (int j = 1; j < K; ++j) a = _mm512_add_ps(a, _mm512_loadu_ps(r[c * K + j] + x));
      m[c] = _mm512_mul_ps(a, vinv);
    }
    stream_transposed4_avx512(m, out + 4 * x);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// 16 floats at p, or (Partial) the lanes in `lanes` with the others zero and unread.
template <bool Partial>
SL_TARGET("avx512f") inline __m512 load16(__mmask16 lanes, const float* p) {
  if constexpr (Partial) return _mm512_maskz_loadu_ps(lanes, p);
  else return _mm512_loadu_ps(p);
}

// The four window means of texels x .. x + 15 for msm_hsum_out_avx512 (m[c]: plane c), the
// window's new bottom row's sums stored into h[c] + x on the way; or (Partial) the lanes in
// `lanes` only, by masked loads (which read nothing past a row's end) and masked stores. The
// lanes left out compute on zeros and are never stored, so each texel gets the same operations
// whichever step it falls in.
template <int K, bool Partial>
SL_TARGET("avx512f") inline void msm_hsum_means16(const float* ext, float* const* h,
                                                  const float* const* r, int x, __mmask16 lanes,
                                                  __m512 vinv, __m512* m) {
  __m512 s[4] = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_ps(),
                 _mm512_setzero_ps()};
  for (int i = 0; i < K; ++i) {
    const __m512 d = load16<Partial>(lanes, ext + x + i), d2 = _mm512_mul_ps(d, d);
    s[0] = _mm512_add_ps(s[0], d);
    s[1] = _mm512_add_ps(s[1], d2);
    s[2] = _mm512_add_ps(s[2], _mm512_mul_ps(d2, d));
    s[3] = _mm512_add_ps(s[3], _mm512_mul_ps(d2, d2));
  }
  for (int c = 0; c < 4; ++c) {
    if constexpr (Partial) _mm512_mask_storeu_ps(h[c] + x, lanes, s[c]);
    else _mm512_storeu_ps(h[c] + x, s[c]);
    __m512 a = s[c];
    if constexpr (K > 1) {
      a = load16<Partial>(lanes, r[c * K] + x);
      for (int j = 1; j < K - 1; ++j)
        a = _mm512_add_ps(a, load16<Partial>(lanes, r[c * K + j] + x));
      a = _mm512_add_ps(a, s[c]);
    }
    m[c] = _mm512_mul_ps(a, vinv);
  }
}

// One 64-byte line of an interleaved output row (4 texels, first texel t0, which may lie before
// the row: t0 < 0) at `line`: a non-temporal store when all four texels are in [0, n), else a
// masked ordinary store of those that are (the rest of the line belongs to other texels).
SL_TARGET("avx512f") inline void store_line4(float* line, int t0, int n, __m512 v) {
  const int lo = std::max(t0, 0), hi = std::min(t0 + 4, n);
  if (lo == t0 && hi == t0 + 4) {
    _mm512_stream_ps(line, v);
  } else if (lo < hi) {
    const unsigned bits = ((1u << (4 * (hi - t0))) - 1u) & ~((1u << (4 * (lo - t0))) - 1u);
    _mm512_mask_storeu_ps(line, __mmask16(bits), v);
  }
}

// msm_hsum_out_avx512 for an output row whose texel 0 lies S texels (16·S bytes) past a 64-byte
// line. The steps run at x = 0, 16, 32, …, so the ring's rows (64-byte aligned, fused_box) are
// read and written on whole lines; output line j (texels 4j − S ..
// 4j − S + 3) is the last S texels of one transposed line and the first 4 − S of the next, one
// valignd, and goes out whole (non-temporal) except at the row's two ends (store_line4).
template <int K, int S>
SL_TARGET("avx512f") void msm_hsum_out_lines(const float* ext, float* const* h,
                                             const float* const* r, int w, __m512 vinv,
                                             float* out) {
  // Line j starts at texel 4j − S's address (16 bytes a texel). Addresses are formed as
  // integers: line 0 may begin before the map's storage (its lanes there are never stored).
  const uintptr_t line0 = reinterpret_cast<uintptr_t>(out) - uintptr_t(16 * S);
  auto line_at = [&](int t0) {  // t0 + S: a multiple of 4
    return reinterpret_cast<float*>(line0 + uintptr_t(16 * (t0 + S)));
  };
  __m512 prev = _mm512_setzero_ps();  // the previous step's texels x − 4 .. x − 1
  int x = 0;
  for (; x < w; x += 16) {
    __m512 m[4];
    if (x + 16 <= w) {
      msm_hsum_means16<K, false>(ext, h, r, x, __mmask16(0xFFFF), vinv, m);
    } else {
      msm_hsum_means16<K, true>(ext, h, r, x, __mmask16((1u << (w - x)) - 1u), vinv, m);
    }
    __m512 line[4];
    transpose4_avx512(m, line);
    for (int q = 0; q < 4; ++q) {
      const int t0 = x + 4 * q - S;
      if constexpr (S == 0) {
        store_line4(line_at(t0), t0, w, line[q]);
      } else {
        // Texels t0 .. t0 + S − 1 from the transposed line before, the rest from line q.
        const __m512 lo = q == 0 ? prev : line[q - 1];
        const __m512 v = _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(
            0xFFFF, _mm512_castps_si512(line[q]), _mm512_castps_si512(lo), 16 - 4 * S));
        store_line4(line_at(t0), t0, w, v);
      }
    }
    prev = line[3];
  }
  if constexpr (S != 0) {
    // The line after the last step's: its first S texels (from the last transposed line).
    const int t0 = x - S;
    const __m512 v = _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(
        0xFFFF, _mm512_setzero_si512(), _mm512_castps_si512(prev), 16 - 4 * S));
    store_line4(line_at(t0), t0, w, v);
  }
}

// hsum_powers_k for the window's new bottom row (its sums into h[0..3]) and
// msm_out_interleaved_avx512 for the output row above it, in one pass of 16 texels at a time:
// rows[c·K + K − 1] is h[c], the K − 1 rows above it are read as before, and the new sums are
// added last from registers (the row order of mean_out_k). The same operations, so the same
// bits (MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoopsBitForBit). Why one pass: the
// output's non-temporal stores (16 B a texel, ~35 MB a cube on the default scene) had a pass of
// their own while the row sums' pass wrote nothing; here the arithmetic can run while they drain
// (~8 % off the cube filter on Zen 5: docs/performance.md).
template <int K>
SL_TARGET("avx512f") void msm_hsum_out_avx512(const float* ext, float* const* h,
                                              const float* const* rows, int w, float inv,
                                              float* out) {
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m512 vinv = _mm512_set1_ps(inv);
  // The map's storage is 16-byte aligned (glibc's), so texel 0 lies 0 to 3 texels past a line;
  // storage that is not (never seen) goes one texel at a time.
  const uintptr_t a = reinterpret_cast<uintptr_t>(out);
  if (a % 16 != 0) {
    for (int x = 0; x < w; ++x) {
      hsum_powers_texel<K>(ext, x, h);
      msm_out_texel<K>(rows, x, inv, out);
    }
    return;
  }
  switch ((a / 16) % 4) {
    case 0: msm_hsum_out_lines<K, 0>(ext, h, r, w, vinv, out); break;
    case 1: msm_hsum_out_lines<K, 1>(ext, h, r, w, vinv, out); break;
    case 2: msm_hsum_out_lines<K, 2>(ext, h, r, w, vinv, out); break;
    default: msm_hsum_out_lines<K, 3>(ext, h, r, w, vinv, out); break;
  }
}

// The AVX2 form of stream_transposed4_avx512: 8 texels, two 64-byte lines.
SL_TARGET("avx2") inline void stream_transposed4_avx2(const __m256* m, float* out) {
  // Within each 128-bit half (texels 4q .. 4q + 3): t0, t1 planes 0 1 interleaved, t2, t3
  // planes 2 3; u_i texel i's four moments in the low half, texel 4 + i's in the high one.
  const __m256 t0 = _mm256_unpacklo_ps(m[0], m[1]), t1 = _mm256_unpackhi_ps(m[0], m[1]);
  const __m256 t2 = _mm256_unpacklo_ps(m[2], m[3]), t3 = _mm256_unpackhi_ps(m[2], m[3]);
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  _mm256_stream_ps(out, _mm256_permute2f128_ps(u0, u1, 0x20));       // texels 0 1
  _mm256_stream_ps(out + 8, _mm256_permute2f128_ps(u2, u3, 0x20));   // 2 3
  _mm256_stream_ps(out + 16, _mm256_permute2f128_ps(u0, u1, 0x31));  // 4 5
  _mm256_stream_ps(out + 24, _mm256_permute2f128_ps(u2, u3, 0x31));  // 6 7
}

// The same in AVX2, 8 texels (one 4 × 8 transpose, two 64-byte lines of streamed stores) per
// step: the AVX2-only machines' fused row (before it: mean_out_k into tmp rows,
// interleave4_row and the stream copy, three passes).
template <int K>
SL_TARGET("avx2") void msm_out_interleaved_avx2(const float* const* rows, int w,
                                                float inv, float* out) {
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) msm_out_texel<K>(rows, x, inv, out);
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m256 vinv = _mm256_set1_ps(inv);
  for (; x + 8 <= w; x += 8) {
    __m256 m[4];
    for (int c = 0; c < 4; ++c) {
      __m256 a = _mm256_loadu_ps(r[c * K] + x);
      for (int j = 1; j < K; ++j) a = _mm256_add_ps(a, _mm256_loadu_ps(r[c * K + j] + x));
      m[c] = _mm256_mul_ps(a, vinv);
    }
    stream_transposed4_avx2(m, out + 4 * x);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// msm_hsum_out_avx512 in AVX2, 8 texels a step.
template <int K>
SL_TARGET("avx2") void msm_hsum_out_avx2(const float* ext, float* const* h,
                                         const float* const* rows, int w, float inv,
                                         float* out) {
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) {
    hsum_powers_texel<K>(ext, x, h);
    msm_out_texel<K>(rows, x, inv, out);
  }
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m256 vinv = _mm256_set1_ps(inv);
  for (; x + 8 <= w; x += 8) {
    __m256 s[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(),
                   _mm256_setzero_ps()};
    for (int i = 0; i < K; ++i) {
      const __m256 d = _mm256_loadu_ps(ext + x + i), d2 = _mm256_mul_ps(d, d);
      s[0] = _mm256_add_ps(s[0], d);
      s[1] = _mm256_add_ps(s[1], d2);
      s[2] = _mm256_add_ps(s[2], _mm256_mul_ps(d2, d));
      s[3] = _mm256_add_ps(s[3], _mm256_mul_ps(d2, d2));
    }
    __m256 m[4];
    for (int c = 0; c < 4; ++c) {
      _mm256_storeu_ps(h[c] + x, s[c]);
      __m256 a = s[c];
      if constexpr (K > 1) {
        a = _mm256_loadu_ps(r[c * K] + x);
        for (int j = 1; j < K - 1; ++j) a = _mm256_add_ps(a, _mm256_loadu_ps(r[c * K + j] + x));
        a = _mm256_add_ps(a, s[c]);
      }
      m[c] = _mm256_mul_ps(a, vinv);
    }
    stream_transposed4_avx2(m, out + 4 * x);
  }
  for (; x < w; ++x) {
    hsum_powers_texel<K>(ext, x, h);
    msm_out_texel<K>(rows, x, inv, out);
  }
}
#endif

}  // namespace

namespace {

// Plane c's filtered row y (a span's columns) goes to row_of(c, y, span, tmp): a row of out[c],
// or (interleaved given) the c-th of four span.n-float rows in tmp, which finish(y, span, tmp)
// then interleaves into row y. The sums are in float (moment_filter.h says why): the powers as
// power_row forms them, each horizontal sum from 0 in window order, the vertical sums in row
// order, then × 1/k² (a float), the same operations on every path.
void power_moments(const float* dist, int w, int h, int k, bool fixed_kernels,
                   const FaceTiles* tiles, std::vector<float>* out,
                   std::vector<float>* interleaved) {
  const size_t n = size_t(w) * size_t(h);
  if (interleaved)
    interleaved->resize(4 * n);
  else
    for (int c = 0; c < 4; ++c) out[c].resize(n);
  const size_t ew = size_t(w) + size_t(k) - 1;
  const float inv = 1.0f / float(k * k);
  auto make_row = [&](int y, const SpanCols& s, float* ext) {
    power_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ew, ext + s.lead);
    for (int c = 0; c < 4; ++c) extend_span(ext + size_t(c) * ew, s, k);
  };
  // Plane c's row y: in the plane, or (interleaving) in tmp's c-th row of s.n floats.
  auto row_of = [&](int c, int y, const SpanCols& s, float* tmp) {
    return interleaved ? tmp + size_t(c) * size_t(s.n)
                       : out[c].data() + size_t(y) * size_t(w) + size_t(s.x0);
  };
  // The interleaved row is made in tmp after the four planes' rows, then streamed into the map
  // (core/stream_copy.h): 16 B per texel is beyond the caches (~35 MB on the default scene's
  // cube), and not reading each line before writing it made the filter 0.55 ms faster and the
  // lookup 0.2 ms slower (AMD EPYC: docs/performance.md).
  const StreamCopy copy = stream_copy_kernel();
#if defined(__x86_64__)
  const Isa isa = interleaved ? exp_path(true) : Isa::scalar;
#endif
  auto finish = [&](int y, const SpanCols& s, float* tmp) {
    if (!interleaved) return;
    float* const row = tmp + 4 * size_t(s.n);
    interleave4_row(tmp, s.n, row);
    copy(row, 4 * size_t(s.n), interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0)));
  };
  // Row y's finite distances over the span's input columns, extended to its window (ext).
  auto finite_ext = [&](int y, const SpanCols& s, float* ext) {
    finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead);
    extend_span(ext, s, k);
  };
  if (fixed_kernels && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        fused_box<float>(
            w, h, k, 4, tiles, dist,
            [&](int y, const SpanCols& s, float* const* dst, float* ext) {
              finite_ext(y, s, ext);
              hsum_powers_k<K>(ext, s.n, dst[0], dst[1], dst[2], dst[3]);
            },
            [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
#if defined(__x86_64__)
              if (isa != Isa::scalar) {
                float* const row =
                    interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
                if (isa == Isa::avx512)
                  msm_out_interleaved_avx512<K>(win, s.n, inv, row);
                else
                  msm_out_interleaved_avx2<K>(win, s.n, inv, row);
                return;
              }
#endif
              // tmp: 8·n of its 10·w floats.
              for (int c = 0; c < 4; ++c) mean_out_k<K>(win + c * K, s.n, inv, row_of(c, y, s, tmp));
              finish(y, s, tmp);
            },
            [&](int y, int row, const SpanCols& s, float* const* dst, const float* const* win,
                float* ext) {
#if defined(__x86_64__)
              if (isa == Isa::scalar) return false;
              finite_ext(row, s, ext);
              float* const out_row =
                  interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
              // The pages output row y + 2 will be streamed into (core/prefetch.h): without the
              // hint the cube filter took ~40 % longer on the default scene.
              if (y + 2 < h) prefetch_pages(out_row + 8 * size_t(w), 16 * size_t(s.n));
              if (isa == Isa::avx512)
                msm_hsum_out_avx512<K>(ext, dst, win, s.n, inv, out_row);
              else
                msm_hsum_out_avx2<K>(ext, dst, win, s.n, inv, out_row);
              return true;
#else
              return false;
#endif
            });
      }))
    return;
  fused_box<float>(
      w, h, k, 4, tiles, dist,
      [&](int y, const SpanCols& s, float* const* dst, float* ext) {
        make_row(y, s, ext);
        for (int c = 0; c < 4; ++c) hsum_row(ext + size_t(c) * ew, s.n, k, dst[c]);
      },
      [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
        // tmp: 4·n floats of plane rows and 4·n of the interleaved row (of its 10·w floats).
        for (int c = 0; c < 4; ++c) vsum_rows(win + c * k, s.n, k, inv, row_of(c, y, s, tmp));
        finish(y, s, tmp);
      });
}

}  // namespace

void filter_power_moments(const float* dist, int w, int h, int k, std::vector<float>* out,
                          const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, out, nullptr);
}

void filter_power_moments_interleaved(const float* dist, int w, int h, int k,
                                      std::vector<float>& moments, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, nullptr, &moments);
}

void filter_power_moments_oracle(const float* dist, int w, int h, int k,
                                 std::vector<float>* out, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, false, tiles, out, nullptr);
}

}  // namespace shadowlab
