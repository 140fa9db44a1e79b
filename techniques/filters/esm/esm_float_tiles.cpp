#include "techniques/filters/esm/esm_float_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/isa.h"
#include "core/exp_log.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "core/simd_target.h"
#include "techniques/pipeline/texel_tiles.h"

namespace shadowlab {
// The file's own namespace: the unity build compiles it with moment_filter.cpp, whose
// anonymous namespace has kernels of the same kind.
namespace esm_float {
namespace {

// A tile's exponentials: 32 + k − 1 rows of kPitch floats (its windows' inputs, k/2 texels
// around its own), computed over whole vectors; the lanes past a row's inputs are never summed.
constexpr int kPitch = 48;  // >= 32 + kEsmFloatMaxWidth − 1, a multiple of 16
constexpr int kMaxRows = kTexelTile + kEsmFloatMaxWidth - 1;

struct Tile {
  int x0, y0, tw, th;
};

// Stages one input row's `n` texels from src as finite distances (d < 1 ? d : 1: NaN and +inf
// give 1), with `lead` copies of the first before them and the last repeated up to `pad_to`
// values (the band's rows: the span's columns and k/2 around them, clamped at the image's edges,
// then padding the vector exponentials may read).
void stage_row_scalar(const float* src, int n, int lead, int pad_to, float* dst) {
  for (int x = 0; x < n; ++x) dst[lead + x] = src[x] < 1.0f ? src[x] : 1.0f;
  for (int x = 0; x < lead; ++x) dst[x] = dst[lead];
  for (int x = lead + n; x < pad_to; ++x) dst[x] = dst[lead + n - 1];
}

#if defined(__x86_64__)
SL_TARGET("avx2") void stage_row_avx2(const float* src, int n, int lead, int pad_to, float* dst) {
  const __m256 one = _mm256_set1_ps(1.0f);
  int x = 0;
  // minps returns its second operand unless the first is smaller: NaN and +inf give 1.
  for (; x + 8 <= n; x += 8)
    _mm256_storeu_ps(dst + lead + x, _mm256_min_ps(_mm256_loadu_ps(src + x), one));
  for (; x < n; ++x) dst[lead + x] = src[x] < 1.0f ? src[x] : 1.0f;
  for (int i = 0; i < lead; ++i) dst[i] = dst[lead];
  for (int i = lead + n; i < pad_to; ++i) dst[i] = dst[lead + n - 1];
}
#endif

void stage_row(Isa isa, const float* src, int n, int lead, int pad_to, float* dst) {
#if defined(__x86_64__)
  if (isa != Isa::scalar) return stage_row_avx2(src, n, lead, pad_to, dst);
#endif
  stage_row_scalar(src, n, lead, pad_to, dst);
}

// A tile's exponentials: dst[yy·kPitch + x] = e^(float(c·(d − s))) of d = src[yy·pitch + x], x < n,
// for `rows` rows; the exponent formed in double, where d − s is exact, and rounded once to
// float, then exp_f (core/exp_log.h). The vector forms also fill the lanes up to the next 8
// (src holds finite values there: the band's padding), which no sum reads.
void exp_rows_scalar(const float* src, size_t pitch, int rows, int n, double c, double s,
                     float* dst) {
  for (int yy = 0; yy < rows; ++yy)
    for (int x = 0; x < n; ++x)
      dst[size_t(yy) * kPitch + size_t(x)] =
          exp_f(float(c * (double(src[size_t(yy) * pitch + size_t(x)]) - s)));
}

#if defined(__x86_64__)
SL_TARGET("avx2") inline __m256 exp8_at(const float* p, __m256d vc, __m256d vs) {
  const __m256 d = _mm256_loadu_ps(p);
  const __m128 lo = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(d)), vs)));
  const __m128 hi = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(d, 1)), vs)));
  return exp_f8(_mm256_set_m128(hi, lo));
}

SL_TARGET("avx2") void exp_rows_avx2(const float* src, size_t pitch, int rows, int n, double c,
                                     double s, bool in_float, float* dst) {
  const __m256d vc = _mm256_set1_pd(c), vs = _mm256_set1_pd(s);
  const __m256 cf = _mm256_set1_ps(float(c)), sf = _mm256_set1_ps(float(s));
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    float* const out = dst + size_t(yy) * kPitch;
    if (in_float) {  // the same bits (in_float_exponent)
      for (int x = 0; x < n; x += 8)
        _mm256_storeu_ps(out + x, exp_f8(_mm256_mul_ps(cf, _mm256_sub_ps(_mm256_loadu_ps(row + x), sf))));
      continue;
    }
    for (int x = 0; x < n; x += 8) _mm256_storeu_ps(out + x, exp8_at(row + x, vc, vs));
  }
}

// 16 lanes while 9 or more values remain, else 8 (exp_f8 gives exp_f16's bits).
// (Zero-masked conversions with every lane on, for GCC 12's -Wmaybe-uninitialized: exp_d8.)
SL_TARGET("avx512f") void exp_rows_avx512(const float* src, size_t pitch, int rows, int n,
                                          double c, double s, bool in_float, float* dst) {
  const __m512d vc = _mm512_set1_pd(c), vs = _mm512_set1_pd(s);
  const __m256d vc4 = _mm256_set1_pd(c), vs4 = _mm256_set1_pd(s);
  const __m512 cf = _mm512_set1_ps(float(c)), sf = _mm512_set1_ps(float(s));
  const __m256 cf8 = _mm256_set1_ps(float(c)), sf8 = _mm256_set1_ps(float(s));
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    float* const out = dst + size_t(yy) * kPitch;
    int x = 0;
    if (in_float) {  // the same bits (in_float_exponent)
      for (; n - x > 8; x += 16)
        _mm512_storeu_ps(out + x, exp_f16(_mm512_mul_ps(cf, _mm512_sub_ps(_mm512_loadu_ps(row + x), sf))));
      if (x < n)
        _mm256_storeu_ps(out + x, exp_f8(_mm256_mul_ps(cf8, _mm256_sub_ps(_mm256_loadu_ps(row + x), sf8))));
      continue;
    }
    for (; n - x > 8; x += 16) {
      const __m512 d = _mm512_loadu_ps(row + x);
      const __m256 lo = _mm512_maskz_cvtpd_ps(
          0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, half_ps(d, 0)), vs)));
      const __m256 hi = _mm512_maskz_cvtpd_ps(
          0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, half_ps(d, 1)), vs)));
      _mm512_storeu_ps(out + x, exp_f16(join_ps(lo, hi)));
    }
    if (x < n) _mm256_storeu_ps(out + x, exp8_at(row + x, vc4, vs4));
  }
}
#endif

// Whether a tile's exponents may be formed in float, c ⊗ (d ⊖ s), with exp_rows_scalar's bits:
// when c and s are floats and hi <= 2·lo, every d of the tile lies within a factor 2 of s
// (lo <= s <= hi), so d − s is exact in float (Sterbenz), and c·(d − s), 24 bits by 24, is
// exact in double and rounds once to float either way. It saves the vector kernels the
// conversions to double and back (a fifth of the exponential's instructions); the scalar
// kernel, the oracle, always takes the double form, so the tests' comparison checks the claim.
bool in_float_exponent(double c, double s, float lo, float hi) {
  return double(float(c)) == c && double(float(s)) == s && lo > 0.0f && hi <= 2.0f * lo;
}

void exp_rows(Isa isa, const float* src, size_t pitch, int rows, int n, double c, double s,
              bool in_float, float* dst) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return exp_rows_avx512(src, pitch, rows, n, c, s, in_float, dst);
  if (isa == Isa::avx2) return exp_rows_avx2(src, pitch, rows, n, c, s, in_float, dst);
#endif
  exp_rows_scalar(src, pitch, rows, n, c, s, dst);
}

// The smallest and largest of `rows` rows of n values (n >= 8 for the vector form, whose last
// load overlaps the one before it: min and max are exact, so the order and the overlap change
// nothing).
void range_scalar(const float* src, size_t pitch, int rows, int n, float& lo, float& hi) {
  for (int yy = 0; yy < rows; ++yy)
    for (int x = 0; x < n; ++x) {
      lo = std::min(lo, src[size_t(yy) * pitch + size_t(x)]);
      hi = std::max(hi, src[size_t(yy) * pitch + size_t(x)]);
    }
}

#if defined(__x86_64__)
SL_TARGET("avx2") void range_avx2(const float* src, size_t pitch, int rows, int n, float& lo,
                                  float& hi) {
  __m256 vlo = _mm256_set1_ps(lo), vhi = _mm256_set1_ps(hi);
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    for (int x = 0; x < n; x += 8) {
      const __m256 d = _mm256_loadu_ps(row + std::min(x, n - 8));
      vlo = _mm256_min_ps(vlo, d);
      vhi = _mm256_max_ps(vhi, d);
    }
  }
  alignas(32) float l[8], u[8];
  _mm256_store_ps(l, vlo);
  _mm256_store_ps(u, vhi);
  for (int i = 0; i < 8; ++i) {
    lo = std::min(lo, l[i]);
    hi = std::max(hi, u[i]);
  }
}
#endif

void range(Isa isa, const float* src, size_t pitch, int rows, int n, float& lo, float& hi) {
#if defined(__x86_64__)
  if (isa != Isa::scalar && n >= 8) return range_avx2(src, pitch, rows, n, lo, hi);
#endif
  range_scalar(src, pitch, rows, n, lo, hi);
}

// A texel's stored value from its window mean a: c·s + ln a = t + e·ln2 + ln m (a = 2^e · m,
// log_split_f; t = c·s), in float with one rounding that matters. t is split into t_hi, a
// multiple of 2^-12 (|t| <= 700: 22 bits), and t_lo = t − t_hi (|t_lo| <= 2^-13); ln2 into
// kLn2Hi12 = 2839/4096 and the rest. big = t_hi + e·kLn2Hi12 is exact (|e| <= 127: e·2839 has
// 19 bits, and the sum is a multiple of 2^-12 below 2^10); small = (t_lo + e·kLn2Lo12) +
// ln m lies within 0.42, where float's roundings are below 3e-8; big + small then rounds once,
// to the stored float. Against the exact c·s + ln a: that half ulp, ln_m_f's 2e-7 and ~1e-8.
// (The double combine, e·ln2 + ln m + t, cost twice the instructions: conversions each way.)
constexpr float kLn2Hi12 = 2839.0f / 4096.0f;
constexpr float kLn2Lo12 = float(0.6931471805599453 - 2839.0 / 4096.0);

struct ShiftTerm {
  float hi, lo;
};

ShiftTerm shift_term(double t) {
  const double hi = std::nearbyint(t * 4096.0) / 4096.0;
  return {float(hi), float(t - hi)};
}

inline float stored_value(float a, ShiftTerm t) {
  int32_t e;
  const float m = log_split_f(a, e);
  const float ef = float(e);
  const float big = t.hi + ef * kLn2Hi12;
  const float small = (t.lo + ef * kLn2Lo12) + ln_m_f(m);
  return big + small;
}

void log_row_scalar(const float* a, int n, ShiftTerm t, float* out) {
  for (int x = 0; x < n; ++x) out[x] = stored_value(a[x], t);
}

#if defined(__x86_64__)
SL_TARGET("avx2") inline __m256 stored_value8(__m256 a, __m256 t_hi, __m256 t_lo) {
  __m256i e;
  const __m256 m = log_split_f8(a, e);
  const __m256 ef = _mm256_cvtepi32_ps(e);
  const __m256 big = _mm256_add_ps(t_hi, _mm256_mul_ps(ef, _mm256_set1_ps(kLn2Hi12)));
  const __m256 small =
      _mm256_add_ps(_mm256_add_ps(t_lo, _mm256_mul_ps(ef, _mm256_set1_ps(kLn2Lo12))), ln_m8(m));
  return _mm256_add_ps(big, small);
}

SL_TARGET("avx512f") inline __m512 stored_value16(__m512 a, __m512 t_hi, __m512 t_lo) {
  __m512i e;
  const __m512 m = log_split_f16(a, e);
  const __m512 ef = _mm512_maskz_cvtepi32_ps(0xFFFF, e);  // zero-masked: exp_d8
  const __m512 big = _mm512_add_ps(t_hi, _mm512_mul_ps(ef, _mm512_set1_ps(kLn2Hi12)));
  const __m512 small =
      _mm512_add_ps(_mm512_add_ps(t_lo, _mm512_mul_ps(ef, _mm512_set1_ps(kLn2Lo12))), ln_m16(m));
  return _mm512_add_ps(big, small);
}
#endif

// The box sums, the same float additions in every path: h[x] = Σ_{i<k} e[x + i] from 0 in i
// order, then a texel's mean (Σ_{j<k} h_j[x] in j order) × inv. The scalar loops (the oracle,
// and the image's last, narrower tiles) run over x, so each texel's additions keep their order.
void hsum(const float* e, int n, int k, float* h) {
  for (int x = 0; x < n; ++x) h[x] = 0.0f;
  for (int i = 0; i < k; ++i)
    for (int x = 0; x < n; ++x) h[x] += e[x + i];
}

void vsum(const float* h, int n, int k, float inv, float* a) {
  for (int x = 0; x < n; ++x) a[x] = h[x];
  for (int j = 1; j < k; ++j)
    for (int x = 0; x < n; ++x) a[x] += h[size_t(j) * kTexelTile + size_t(x)];
  for (int x = 0; x < n; ++x) a[x] *= inv;
}

void box_tile_scalar(const float* ebuf, int tw, int th, int k, ShiftTerm t, float* hbuf,
                     float* abuf, float* out, int w) {
  for (int yy = 0; yy < th + k - 1; ++yy)
    hsum(ebuf + size_t(yy) * kPitch, tw, k, hbuf + size_t(yy) * kTexelTile);
  const float inv = 1.0f / float(k * k);
  for (int y = 0; y < th; ++y) {
    vsum(hbuf + size_t(y) * kTexelTile, tw, k, inv, abuf);
    log_row_scalar(abuf, tw, t, out + size_t(y) * size_t(w));
  }
}

#if defined(__x86_64__)
// A whole tile's sums (32 columns) in 4 (AVX2) or 2 (AVX-512) registers per row, and each output
// row's mean straight into the logarithm: the scalar loops' additions in their order.
SL_TARGET("avx2") void box_tile_avx2(const float* ebuf, int th, int k, ShiftTerm t, float* hbuf,
                                     float* out, int w) {
  for (int yy = 0; yy < th + k - 1; ++yy) {
    const float* e = ebuf + size_t(yy) * kPitch;
    __m256 a[4];
    for (int q = 0; q < 4; ++q) a[q] = _mm256_setzero_ps();
    for (int i = 0; i < k; ++i)
      for (int q = 0; q < 4; ++q) a[q] = _mm256_add_ps(a[q], _mm256_loadu_ps(e + 8 * q + i));
    for (int q = 0; q < 4; ++q) _mm256_storeu_ps(hbuf + size_t(yy) * kTexelTile + 8 * q, a[q]);
  }
  const __m256 inv = _mm256_set1_ps(1.0f / float(k * k));
  const __m256 t_hi = _mm256_set1_ps(t.hi), t_lo = _mm256_set1_ps(t.lo);
  for (int y = 0; y < th; ++y) {
    const float* hrow = hbuf + size_t(y) * kTexelTile;
    float* const o = out + size_t(y) * size_t(w);
    for (int q = 0; q < 4; ++q) {
      __m256 a = _mm256_loadu_ps(hrow + 8 * q);
      for (int j = 1; j < k; ++j)
        a = _mm256_add_ps(a, _mm256_loadu_ps(hrow + size_t(j) * kTexelTile + 8 * q));
      _mm256_storeu_ps(o + 8 * q, stored_value8(_mm256_mul_ps(a, inv), t_hi, t_lo));
    }
  }
}

SL_TARGET("avx512f") void box_tile_avx512(const float* ebuf, int th, int k, ShiftTerm t,
                                          float* hbuf, float* out, int w) {
  for (int yy = 0; yy < th + k - 1; ++yy) {
    const float* e = ebuf + size_t(yy) * kPitch;
    __m512 a0 = _mm512_setzero_ps(), a1 = _mm512_setzero_ps();
    for (int i = 0; i < k; ++i) {
      a0 = _mm512_add_ps(a0, _mm512_loadu_ps(e + i));
      a1 = _mm512_add_ps(a1, _mm512_loadu_ps(e + 16 + i));
    }
    _mm512_storeu_ps(hbuf + size_t(yy) * kTexelTile, a0);
    _mm512_storeu_ps(hbuf + size_t(yy) * kTexelTile + 16, a1);
  }
  const __m512 inv = _mm512_set1_ps(1.0f / float(k * k));
  const __m512 t_hi = _mm512_set1_ps(t.hi), t_lo = _mm512_set1_ps(t.lo);
  for (int y = 0; y < th; ++y) {
    const float* hrow = hbuf + size_t(y) * kTexelTile;
    float* const o = out + size_t(y) * size_t(w);
    for (int q = 0; q < 2; ++q) {
      __m512 a = _mm512_loadu_ps(hrow + 16 * q);
      for (int j = 1; j < k; ++j)
        a = _mm512_add_ps(a, _mm512_loadu_ps(hrow + size_t(j) * kTexelTile + 16 * q));
      _mm512_storeu_ps(o + 16 * q, stored_value16(_mm512_mul_ps(a, inv), t_hi, t_lo));
    }
  }
}
#endif

// Filters tile t from its band's staged rows (`band`: the span's finite, edge-extended input
// rows; `col`: the tile's first window column in them) into out (the face's image), shifted by
// the middle s of its inputs' range; false, writing nothing, when that range is too wide.
bool filter_tile(Isa isa, const float* band, size_t band_pitch, int col, int k, double c,
                 const Tile& t, float* ebuf, float* hbuf, float* abuf, float* o, int w) {
  const int rows = t.th + k - 1, n = t.tw + k - 1;
  const float* const src = band + size_t(col);
  float lo = 1.0f, hi = 0.0f;
  range(isa, src, band_pitch, rows, n, lo, hi);
  // s: the float nearest the middle (in [lo, hi], as lo and hi are floats).
  const double s = double(float((double(lo) + double(hi)) * 0.5));
  if (!(c * std::max(double(hi) - s, s - double(lo)) <= kEsmFloatExponent)) return false;
  exp_rows(isa, src, band_pitch, rows, n, c, s, in_float_exponent(c, s, lo, hi), ebuf);
  const ShiftTerm shift = shift_term(c * s);
#if defined(__x86_64__)
  if (t.tw == kTexelTile && isa == Isa::avx512) {
    box_tile_avx512(ebuf, t.th, k, shift, hbuf, o, w);
    return true;
  }
  if (t.tw == kTexelTile && isa == Isa::avx2) {
    box_tile_avx2(ebuf, t.th, k, shift, hbuf, o, w);
    return true;
  }
#endif
  box_tile_scalar(ebuf, t.tw, t.th, k, shift, hbuf, abuf, o, w);
  return true;
}

// Asks for a tile's output rows (columns x0 .. x0 + tw − 1 of rows y0 .. y0 + th − 1) in the
// exclusive state, the next tile's while this one is computed (the first's while its span is
// staged): a tile's 32 short rows a face's width apart are stores to lines no cache holds (the
// map is larger than the caches), and without it those stores stalled the kernels (the cube's
// filter ~8 % slower on the default scene). A prefetch changes no value.
void prefetch_output(const float* out, int w, int y0, int th, int x0, int tw) {
  for (int y = 0; y < th; ++y) {
    const float* p = out + size_t(y0 + y) * size_t(w) + size_t(x0);
    __builtin_prefetch(p, 1, 3);
    __builtin_prefetch(p + tw - 1, 1, 3);
  }
}

Isa pick_isa(bool simd) { return simd ? process_isa() : Isa::scalar; }

}  // namespace
}  // namespace esm_float

size_t esm_float_tiles(const float* dist, int w, int h, int k, double c, bool simd,
                       const FaceTiles* tiles, float* out, FaceTiles& rest) {
  using namespace esm_float;
  const int r = k / 2;
  const int tx_n = (w + kTexelTile - 1) / kTexelTile, ty_n = (h + kTexelTile - 1) / kTexelTile;
  rest.tiles_x = tx_n;
  rest.tiles_y = ty_n;
  rest.need.assign(size_t(tx_n) * size_t(ty_n), 0);
  const bool every = tiles == nullptr || tiles->every();
  const Isa isa = pick_isa(simd);
  std::vector<size_t> left(static_cast<size_t>(ty_n), 0);
  // Each band of 32 rows first stages its spans' input rows (the runs of needed tiles, k/2
  // columns and rows around them, clamped at the image's edges) whole: whole rows are read in
  // sequence, which the hardware prefetcher follows (and the next row is asked for a row ahead:
  // the render wrote the face long before), where a tile's 32 + k − 1 short rows a face's width
  // apart stalled on every row. The tiles then read that band, in cache.
  // + 8: the vector exponentials' last lanes (exp_rows) read up to 7 values past a row.
  const size_t band_pitch = size_t(w) + size_t(k) - 1 + 8;
  parallel_for_chunks(size_t(ty_n), 1, [&](size_t b0, size_t b1) {
    const size_t n_band = size_t(kMaxRows) * band_pitch;
    const std::unique_ptr<float[]> buf(new float[n_band + size_t(kMaxRows) * kPitch +
                                                 size_t(kMaxRows) * kTexelTile + kTexelTile]);
    float* const band = buf.get();
    float* const ebuf = band + n_band;
    float* const hbuf = ebuf + size_t(kMaxRows) * kPitch;
    float* const abuf = hbuf + size_t(kMaxRows) * kTexelTile;
    std::vector<TexelSpan> spans;
    for (size_t ty = b0; ty < b1; ++ty) {
      tile_spans(every ? nullptr : tiles, int(ty), w, spans);
      const int y0 = int(ty) * kTexelTile, th = std::min(kTexelTile, h - y0);
      for (const TexelSpan& span : spans) {
        const int in0 = std::max(0, span.x0 - r), in1 = std::min(w, span.x1 + r);
        const int lead = in0 - (span.x0 - r), width = span.x1 - span.x0 + k - 1;
        prefetch_output(out, w, y0, th, span.x0, std::min(kTexelTile, span.x1 - span.x0));
        for (int yy = 0; yy < th + k - 1; ++yy) {
          const int y = std::clamp(y0 - r + yy, 0, h - 1);
          const int y_next = std::clamp(y0 - r + yy + 1, 0, h - 1);
          if (y_next != y)  // a prefetch changes no value
            prefetch_bytes(dist + size_t(y_next) * size_t(w) + size_t(in0),
                           size_t(in1 - in0) * sizeof(float));
          stage_row(isa, dist + size_t(y) * size_t(w) + size_t(in0), in1 - in0, lead, width + 8,
                    band + size_t(yy) * band_pitch);
        }
        for (int x0 = span.x0; x0 < span.x1; x0 += kTexelTile) {
          if (x0 + kTexelTile < span.x1)
            prefetch_output(out, w, y0, th, x0 + kTexelTile,
                            std::min(kTexelTile, span.x1 - x0 - kTexelTile));
          const Tile t{x0, y0, std::min(kTexelTile, span.x1 - x0), th};
          if (!filter_tile(isa, band, band_pitch, x0 - span.x0, k, c, t, ebuf, hbuf, abuf,
                           out + size_t(y0) * size_t(w) + size_t(x0), w)) {
            rest.need[ty * size_t(tx_n) + size_t(x0 / kTexelTile)] = 1;
            ++left[ty];
          }
        }
      }
    }
  });
  size_t n = 0;
  for (const size_t l : left) n += l;
  return n;
}

}  // namespace shadowlab
