#include "techniques/lookup/poisson_disk.h"

#include <vector>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"

namespace shadowlab {

PoissonDisk poisson_disk(int n) {
  SL_CHECK(n >= 1 && n <= 256);
  PoissonDisk d;
  float r = 0.85f * std::sqrt(1.0f / float(n));
  uint64_t candidate = 0;
  int rejected = 0;
  while (int(d.points.size()) < n) {
    const uint64_t h = rng_hash(candidate, 0, uint64_t(n), 0);
    ++candidate;
    const vec2 q(2.0f * rng_float(h) - 1.0f, 2.0f * rng_float(mix64(h)) - 1.0f);
    if (glm::dot(q, q) > 1.0f) continue;  // outside the disk: not a candidate
    bool ok = true;
    for (const vec2& p : d.points) ok = ok && glm::distance(p, q) >= r;
    if (ok) {
      d.points.push_back(q);
      continue;
    }
    if (++rejected >= 200 * n) {
      r *= 0.95f;
      rejected = 0;
    }
  }
  d.min_distance = n > 1 ? 2.0f : 0.0f;
  for (size_t i = 0; i < d.points.size(); ++i)
    for (size_t j = i + 1; j < d.points.size(); ++j)
      d.min_distance = std::min(d.min_distance, glm::distance(d.points[i], d.points[j]));
  return d;
}

namespace {

// (cos, sin) of the 4096 angles 2π·(k + ½)/4096, computed once in double.
constexpr int kAngles = 4096;
const std::vector<vec2>& rotation_table() {
  static const std::vector<vec2> table = [] {
    std::vector<vec2> t(kAngles);
    for (int k = 0; k < kAngles; ++k) {
      const double angle = 6.283185307179586 * (double(k) + 0.5) / double(kAngles);
      t[size_t(k)] = vec2(float(std::cos(angle)), float(std::sin(angle)));
    }
    return t;
  }();
  return table;
}

}  // namespace

vec2 poisson_rotation(size_t pixel) {
  // The hash's top 12 bits pick one of 4096 angles: a table read instead of a sin and a cos per
  // pixel (they were a fifth of the Poisson lookup's time), and 0.09° steps are far below what
  // a 4-64-tap pattern can show.
  return rotation_table()[size_t(rng_hash(pixel, 0, 0x9015504eull) >> 52)];
}

}  // namespace shadowlab
