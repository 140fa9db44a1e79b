#include "metric/detail.h"

#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace shadowlab {
namespace {

// LSD radix sort of 32-bit keys, three 11-bit digits; a digit shared by every key is skipped.
void radix_sort(std::vector<uint32_t>& keys, std::vector<uint32_t>& tmp) {
  constexpr int kBits = 11;
  constexpr uint32_t kBuckets = 1u << kBits;
  tmp.resize(keys.size());
  for (int shift = 0; shift < 32; shift += kBits) {
    std::array<size_t, kBuckets> count{};
    for (const uint32_t k : keys) ++count[(k >> shift) & (kBuckets - 1)];
    if (count[(keys.front() >> shift) & (kBuckets - 1)] == keys.size()) continue;
    size_t offset = 0;
    for (size_t& c : count) {
      const size_t n = c;
      c = offset;
      offset += n;
    }
    for (const uint32_t k : keys) tmp[count[(k >> shift) & (kBuckets - 1)]++] = k;
    keys.swap(tmp);
  }
}

}  // namespace

double texel_share_ratio(const ImageU32& texels) {
  DetailScratch scratch;
  return texel_share_ratio(texels, scratch);
}

double texel_share_ratio(const ImageU32& texels, DetailScratch& scratch) {
  std::vector<uint32_t>& keys = scratch.keys;
  keys.clear();
  keys.reserve(texels.data.size());
  for (const uint32_t t : texels.data)
    if (t != kNoTexel) keys.push_back(t);
  if (keys.empty()) return 0.0;
  radix_sort(keys, scratch.swap);
  // Each texel with n pixels contributes n pixels of value n: Σ n² per pixel = Σ n³ per texel.
  // Every term is an integer below 2^53 for any realistic count, and the order is fixed.
  double sum_cubes = 0.0;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    const double n = double(j - i);
    sum_cubes += n * n * n;
    i = j;
  }
  return std::sqrt(sum_cubes / double(keys.size()));
}

double detail_score(const ImageU32* texels) {
  DetailScratch scratch;
  return detail_score(texels, scratch);
}

double detail_score(const ImageU32* texels, DetailScratch& scratch) {
  if (!texels) return 1.0;
  const double s = texel_share_ratio(*texels, scratch);
  return s > 0.0 ? 1.0 / s : 1.0;
}

}  // namespace shadowlab
