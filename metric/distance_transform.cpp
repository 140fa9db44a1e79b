#include "metric/distance_transform.h"

#include <algorithm>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {

void squared_distance_1d(const int32_t* f, int n, int32_t* d, EnvelopeScratch& s) {
  if (n <= 0) return;
  s.site.resize(size_t(n));
  s.num.resize(size_t(n) + 1);
  s.den.resize(size_t(n) + 1);
  int* v = s.site.data();
  int64_t* zn = s.num.data();
  int64_t* zd = s.den.data();
  // Envelope boundaries are fractions zn/zd with zd > 0; ±infinity is encoded as (∓1 or ±1, 0)
  // and handled by the comparisons below.
  auto at_or_left_of = [&](int64_t num, int64_t den, int k) {  // num/den ≤ z[k] ?
    if (zd[k] == 0) return zn[k] > 0;                          // z[k] = ±inf
    return num * zd[k] <= zn[k] * den;
  };

  // Build the lower envelope from the sites only; a kNoSite sample is no parabola.
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kNoSite) continue;
    const int64_t fq = f[q] + int64_t(q) * q;
    if (k < 0) {
      k = 0;
      v[0] = q;
      zn[0] = -1, zd[0] = 0;  // −inf
      zn[1] = 1, zd[1] = 0;   // +inf
      continue;
    }
    // The new parabola meets the rightmost envelope parabola p at s = num/den; envelope
    // parabolas that start at or right of s are hidden. z[0] = −inf stops the loop at k = 0.
    int64_t num, den;
    for (;;) {
      const int p = v[k];
      num = fq - (f[p] + int64_t(p) * p);
      den = 2 * int64_t(q - p);
      if (at_or_left_of(num, den, k)) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    v[k] = q;
    zn[k] = num, zd[k] = den;
    zn[k + 1] = 1, zd[k + 1] = 0;
  }

  if (k < 0) {
    std::fill(d, d + n, kNoSite);
    return;
  }
  // Read the envelope back at every integer position: advance while z[k+1] < q.
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (zd[k + 1] != 0 && zn[k + 1] < int64_t(q) * zd[k + 1]) ++k;
    const int32_t dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

void column_squared_distances(const ImageU8& mask, uint8_t bits, std::vector<int32_t>& out) {
  SL_CHECK_EQ(mask.channels, 1);
  const size_t W = size_t(mask.width);
  const size_t H = size_t(mask.height);
  out.resize(W * H);
  if (W == 0 || H == 0) return;
  // kFar = no set pixel in that direction yet; far below INT32_MAX so kFar + 1 cannot
  // overflow, and above any real distance (< kMaxImageSide), so min() keeps it "far".
  constexpr int32_t kFar = 1 << 30;
  const uint8_t* m = mask.plane(0);
  int32_t* g = out.data();
  // Per chunk of columns: a downward scan (distance to the nearest set pixel at or above), then
  // an upward scan (at or below) that also squares each finished row in place. Branch-free
  // selects, so the pixel loops vectorize.
  parallel_for_chunks(W, 256, [&, bits](size_t x0, size_t x1) {
    for (size_t x = x0; x < x1; ++x) g[x] = kFar * int32_t((m[x] & bits) == 0);
    for (size_t y = 1; y < H; ++y) {
      const uint8_t* in = m + y * W;
      int32_t* row = g + y * W;
      const int32_t* above = row - W;
      for (size_t x = x0; x < x1; ++x)
        row[x] = std::min(above[x] + 1, kFar) * int32_t((in[x] & bits) == 0);
    }
    // Upward: row y + 1 is already squared, so its unsquared distance is kept in `below`.
    std::vector<int32_t> below(x1 - x0, kFar);
    for (size_t y = H; y-- > 0;) {
      int32_t* row = g + y * W;
      for (size_t x = x0; x < x1; ++x) {
        const int32_t d = std::min(row[x], below[x - x0] + 1);
        below[x - x0] = d;
        row[x] = d >= kFar ? kNoSite : d * d;
      }
    }
  });
}

ImageD squared_distance_transform(const ImageU8& mask, uint8_t bits) {
  const int w = mask.width;
  const int h = mask.height;
  ImageD out(w, h, 1);
  if (mask.empty()) return out;
  const size_t W = size_t(w);
  std::vector<int32_t> col;
  column_squared_distances(mask, bits, col);
  double* dst = out.plane(0);
  parallel_for_chunks(size_t(h), 16, [&](size_t y0, size_t y1) {
    EnvelopeScratch scratch;
    std::vector<int32_t> d(W);
    for (size_t y = y0; y < y1; ++y) {
      squared_distance_1d(col.data() + y * W, w, d.data(), scratch);
      for (size_t x = 0; x < W; ++x)
        dst[y * W + x] = d[x] == kNoSite ? std::numeric_limits<double>::infinity() : double(d[x]);
    }
  });
  return out;
}

}  // namespace shadowlab
