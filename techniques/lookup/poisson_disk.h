#pragma once
// A fixed Poisson-disk pattern: n points in the unit disk, no two closer than the spacing the
// dart throwing reached. A pure function of n (counter-based random numbers, core/rng.h), so
// every lookup and every thread sees the same pattern.
#include <cstddef>
#include <vector>

#include "core/math.h"

namespace shadowlab {

struct PoissonDisk {
  std::vector<vec2> points;  // in the unit disk, in acceptance order
  float min_distance = 0.0f;  // the smallest distance between two points
};

// Dart throwing: candidates uniform in the disk are accepted when at least r from every accepted
// point; r starts at 0.85·√(1/n) (close to the densest random packing's spacing) and shrinks by
// 5 % after every 200·n rejected candidates until n points are in. n in [1, 256].
PoissonDisk poisson_disk(int n);

// The per-pixel rotation of the pattern, (cos θ, sin θ) with θ one of 4096 equally spaced angles
// in [0, 2π), picked by the counter-based hash of the pixel index (core/rng.h): the same for a
// pixel on every run and thread count, different from pixel to pixel.
vec2 poisson_rotation(size_t pixel);

}  // namespace shadowlab
