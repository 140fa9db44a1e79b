#include "techniques/filters/esm/esm_float_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/isa.h"
#include "core/exp_log.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "techniques/filters/esm/esm_tile_rows.h"
#include "techniques/pipeline/texel_tiles.h"

namespace shadowlab {
// The file's own namespace: the unity build compiles it with moment_filter.cpp, whose
// anonymous namespace has kernels of the same kind.
namespace esm_float {
namespace {

// A tile's exponentials: 32 + k − 1 rows of kPitch floats (its windows' inputs, k/2 texels
// around its own); the kernels are techniques/filters/esm/esm_tile_rows.h's.
constexpr int kPitch = kEsmTilePitch;
static_assert(kEsmTileWidth == kTexelTile);
static_assert(kPitch >= kTexelTile + kEsmFloatMaxWidth - 1 && kPitch % 16 == 0);
constexpr int kMaxRows = kTexelTile + kEsmFloatMaxWidth - 1;

struct Tile {
  int x0, y0, tw, th;
};

// Whether a tile's exponents may be formed in float, c ⊗ (d ⊖ s), with the scalar table's
// exp_rows' bits: when c and s are floats and hi <= 2·lo, every d of the tile lies within a factor 2 of s
// (lo <= s <= hi), so d − s is exact in float (Sterbenz), and c·(d − s), 24 bits by 24, is
// exact in double and rounds once to float either way. It saves the vector kernels the
// conversions to double and back (a fifth of the exponential's instructions); the scalar
// kernel, the oracle, always takes the double form, so the tests' comparison checks the claim.
bool in_float_exponent(double c, double s, float lo, float hi) {
  return double(float(c)) == c && double(float(s)) == s && lo > 0.0f && hi <= 2.0f * lo;
}

// A texel's stored value from its window mean a: c·s + ln a = t + e·ln2 + ln m (a = 2^e · m,
// log_split_f; t = c·s), in float with one rounding that matters. t is split into t_hi, a
// multiple of 2^-12 (|t| <= 700: 22 bits), and t_lo = t − t_hi (|t_lo| <= 2^-13); ln2 into
// kLn2Hi12 = 2839/4096 and the rest. big = t_hi + e·kLn2Hi12 is exact (|e| <= 127: e·2839 has
// 19 bits, and the sum is a multiple of 2^-12 below 2^10); small = (t_lo + e·kLn2Lo12) +
// ln m lies within 0.42, where float's roundings are below 3e-8; big + small then rounds once,
// to the stored float. Against the exact c·s + ln a: that half ulp, ln_m_f's 2e-7 and ~1e-8.
// (The double combine, e·ln2 + ln m + t, cost twice the instructions: conversions each way.)
constexpr float kLn2Hi12 = kEsmLn2Hi12;
constexpr float kLn2Lo12 = kEsmLn2Lo12;

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

// Filters tile t from its band's staged rows (`band`: the span's finite, edge-extended input
// rows; `col`: the tile's first window column in them) into out (the face's image), shifted by
// the middle s of its inputs' range; false, writing nothing, when that range is too wide.
bool filter_tile(const EsmTileKernels& kt, const float* band, size_t band_pitch, int col, int k,
                 double c, const Tile& t, float* ebuf, float* hbuf, float* abuf, float* o, int w) {
  const int rows = t.th + k - 1, n = t.tw + k - 1;
  const float* const src = band + size_t(col);
  float lo = 1.0f, hi = 0.0f;
  kt.range(src, band_pitch, rows, n, lo, hi);
  // s: the float nearest the middle (in [lo, hi], as lo and hi are floats).
  const double s = double(float((double(lo) + double(hi)) * 0.5));
  if (!(c * std::max(double(hi) - s, s - double(lo)) <= kEsmFloatExponent)) return false;
  kt.exp_rows(src, band_pitch, rows, n, c, s, in_float_exponent(c, s, lo, hi), ebuf);
  const ShiftTerm shift = shift_term(c * s);
  if (t.tw == kTexelTile && kt.box_tile) {
    kt.box_tile(ebuf, t.th, k, shift.hi, shift.lo, hbuf, o, w);
    return true;
  }
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
  const EsmTileKernels& kt = esm_tile_kernels(simd ? process_isa() : Isa::scalar);
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
          kt.stage_row(dist + size_t(y) * size_t(w) + size_t(in0), in1 - in0, lead, width + 8,
                    band + size_t(yy) * band_pitch);
        }
        for (int x0 = span.x0; x0 < span.x1; x0 += kTexelTile) {
          if (x0 + kTexelTile < span.x1)
            prefetch_output(out, w, y0, th, x0 + kTexelTile,
                            std::min(kTexelTile, span.x1 - x0 - kTexelTile));
          const Tile t{x0, y0, std::min(kTexelTile, span.x1 - x0), th};
          if (!filter_tile(kt, band, band_pitch, x0 - span.x0, k, c, t, ebuf, hbuf, abuf,
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
