#include "metric/contour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metric/image_reuse.h"

namespace shadowlab {
namespace {

// OR of all pixel values: which bits (levels) have any contour pixel.
uint8_t bits_present(const ImageU8& m) {
  uint8_t any = 0;
  for (const uint8_t v : m.data) any |= v;
  return any;
}

// contour_distance_rms with a caller-owned column buffer (reused across levels).
double distance_rms(const ImageU8& test_contour, const ImageU8& ref_contour, uint8_t bits,
                    std::vector<int32_t>& col) {
  SL_CHECK(test_contour.width == ref_contour.width && test_contour.height == ref_contour.height);
  if (!(bits_present(test_contour) & bits)) return std::numeric_limits<double>::infinity();
  const int w = ref_contour.width;
  const size_t W = size_t(w);
  const size_t H = size_t(ref_contour.height);
  column_squared_distances(test_contour, bits, col);
  // Row phase only where the reference has contour pixels; exact integer sums per row.
  std::vector<int64_t> row_sum(H, 0), row_count(H, 0);
  parallel_for_chunks(H, 16, [&](size_t y0, size_t y1) {
    EnvelopeScratch scratch;
    std::vector<int32_t> d;
    for (size_t y = y0; y < y1; ++y) {
      const uint8_t* r = ref_contour.plane(0) + y * W;
      if (std::none_of(r, r + W, [&](uint8_t v) { return (v & bits) != 0; })) continue;
      d.resize(W);
      squared_distance_1d(col.data() + y * W, w, d.data(), scratch);
      int64_t s = 0, n = 0;
      for (size_t x = 0; x < W; ++x) {
        if (r[x] & bits) {
          s += d[x];
          ++n;
        }
      }
      row_sum[y] = s;
      row_count[y] = n;
    }
  });
  int64_t sum = 0, count = 0;
  for (size_t y = 0; y < H; ++y) {
    sum += row_sum[y];
    count += row_count[y];
  }
  SL_CHECK(count > 0);
  return std::sqrt(double(sum) / double(count));
}

double score_from(const ImageU8& ct, const ImageU8& cr, uint8_t bit, uint8_t test_has,
                  uint8_t ref_has, std::vector<int32_t>& col) {
  const bool t = test_has & bit;
  const bool r = ref_has & bit;
  if (!t && !r) return 1.0;
  if (t != r) return 0.0;
  const double d_rms = distance_rms(ct, cr, bit, col);
  const double d_max = contour_max_distance(cr.width, cr.height);
  return std::clamp(1.0 - d_rms / d_max, 0.0, 1.0);
}

void check_same_size(const ImageD& a, const ImageD& b) {
  if (a.width != b.width || a.height != b.height || a.channels != 1 || b.channels != 1)
    throw InputError("metric", "contour score needs two 1-channel images of the same size");
}

}  // namespace

ImageU8 contour_bits(const ImageD& blurred, std::span<const double> levels) {
  ImageU8 out;
  contour_bits(blurred, levels, out);
  return out;
}

void contour_bits(const ImageD& blurred, std::span<const double> levels, ImageU8& out) {
  SL_CHECK_EQ(blurred.channels, 1);
  SL_CHECK(levels.size() <= 8);
  const int w = blurred.width;
  const int h = blurred.height;
  reshape_image(out, w, h);
  if (blurred.empty()) return;
  const size_t W = size_t(w);
  const double* b = blurred.plane(0);
  uint8_t* dst = out.plane(0);
  parallel_for_chunks(size_t(h), 32, [&](size_t y0, size_t y1) {
    std::vector<double> lo(W), hi(W);
    for (size_t y = y0; y < y1; ++y) {
      // Block min/max: over rows y and y + 1 (just row y on the last row) ...
      const double* r0 = b + y * W;
      const double* r1 = y + 1 < size_t(h) ? r0 + W : r0;
      for (size_t x = 0; x < W; ++x) {
        lo[x] = std::min(r0[x], r1[x]);
        hi[x] = std::max(r0[x], r1[x]);
      }
      // ... then over columns x and x + 1 (just column x on the last column), in place.
      for (size_t x = 0; x + 1 < W; ++x) {
        lo[x] = std::min(lo[x], lo[x + 1]);
        hi[x] = std::max(hi[x], hi[x + 1]);
      }
      uint8_t* o = dst + y * W;
      std::fill(o, o + W, uint8_t(0));
      for (size_t l = 0; l < levels.size(); ++l) {
        const double c = levels[l];
        const uint8_t bit = uint8_t(1u << l);
        for (size_t x = 0; x < W; ++x) o[x] |= (lo[x] <= c && c <= hi[x]) ? bit : uint8_t(0);
      }
    }
  });
}

ImageU8 contour_mask(const ImageD& blurred, double level) {
  const double levels[1] = {level};
  return contour_bits(blurred, levels);
}

double contour_distance_rms(const ImageU8& test_contour, const ImageU8& ref_contour, uint8_t bits) {
  std::vector<int32_t> col;
  return distance_rms(test_contour, ref_contour, bits, col);
}

double contour_max_distance(int width, int height) {
  return 0.2 * std::sqrt(double(width) * double(height));
}

double contour_score(const ImageD& blurred_test, const ImageD& blurred_ref, double level) {
  check_same_size(blurred_test, blurred_ref);
  const ImageU8 ct = contour_mask(blurred_test, level);
  const ImageU8 cr = contour_mask(blurred_ref, level);
  std::vector<int32_t> col;
  return score_from(ct, cr, 1, bits_present(ct), bits_present(cr), col);
}

std::array<double, 3> contour_scores(const ImageD& blurred_test, const ImageD& blurred_ref) {
  ContourScratch scratch;
  return contour_scores(blurred_test, blurred_ref, scratch);
}

std::array<double, 3> contour_scores(const ImageD& blurred_test, const ImageD& blurred_ref,
                                     ContourScratch& scratch) {
  check_same_size(blurred_test, blurred_ref);
  contour_bits(blurred_test, kContourLevels, scratch.test);
  contour_bits(blurred_ref, kContourLevels, scratch.ref);
  const uint8_t test_has = bits_present(scratch.test);
  const uint8_t ref_has = bits_present(scratch.ref);
  std::array<double, 3> scores{};
  for (size_t l = 0; l < scores.size(); ++l)
    scores[l] =
        score_from(scratch.test, scratch.ref, uint8_t(1u << l), test_has, ref_has, scratch.column);
  return scores;
}

}  // namespace shadowlab
