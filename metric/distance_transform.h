#pragma once
// Exact Euclidean distance transform in O(N) (Felzenszwalb & Huttenlocher, "Distance Transforms
// of Sampled Functions", 2012): the lower envelope of parabolas, one dimension at a time.
// Squared pixel distances are integers, so the whole transform runs in exact integer arithmetic
// (int32 distances; the parabola intersections are compared as int64 fractions, never divided).
#include <cstdint>
#include <limits>
#include <vector>

#include "core/image.h"
#include "metric/box_blur.h"

namespace shadowlab {

// Binary mask: a pixel is set when (value & bits) != 0 for the bits asked for.
using ImageU8 = Image<uint8_t>;

// "No site on this line" in the integer transforms (plays +infinity).
constexpr int32_t kNoSite = std::numeric_limits<int32_t>::max();

// Scratch space of the 1D transform (reused across lines to avoid allocations).
struct EnvelopeScratch {
  std::vector<int> site;     // parabola apexes of the lower envelope
  std::vector<int64_t> num;  // parabola i is lowest from num[i]/den[i] on
  std::vector<int64_t> den;
};

// 1D squared distance transform of a sampled integer function: d[q] = min over p of
// (q − p)² + f[p], q in [0, n). f[p] = kNoSite means no parabola at p; d is kNoSite everywhere
// when every f is. Requires 0 ≤ f ≤ 2^30 for sites and n ≤ 16384, so every d fits in int32.
void squared_distance_1d(const int32_t* f, int n, int32_t* d, EnvelopeScratch& scratch);

// Column phase of the 2D transform: for every pixel, the squared distance (pixels²) to the
// nearest set pixel of its own column, or kNoSite; row-major W × H, written to `out` (resized;
// pass the same vector again to reuse its memory). Two scans per column (the exact 1D transform
// of a binary line).
void column_squared_distances(const ImageU8& mask, uint8_t bits, std::vector<int32_t>& out);

// Squared Euclidean distance (pixels², exact integers) from every pixel centre to the nearest
// set pixel centre of `mask` (1 channel); 0 on set pixels, +infinity everywhere when no pixel is
// set. Columns first, then the lower envelope along each row. Independent of the thread count.
ImageD squared_distance_transform(const ImageU8& mask, uint8_t bits = 0xFF);

}  // namespace shadowlab
