#include "techniques/pipeline/depth_quantize.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {

const std::vector<std::string>& depth_format_names() {
  static const std::vector<std::string> names = {"f32", "16", "8", "8cubic"};
  return names;
}

DepthFormat depth_format_from_name(const std::string& name) {
  const auto& n = depth_format_names();
  const auto it = std::find(n.begin(), n.end(), name);
  SL_CHECK(it != n.end());
  return DepthFormat(it - n.begin());
}

float quantize_depth(float d, DepthFormat f) {
  if (f == DepthFormat::F32 || !(d < INFINITY)) return d;
  const double x = std::clamp(double(d), 0.0, 1.0);
  switch (f) {
    case DepthFormat::U16:
      return float(std::nearbyint(x * 65535.0) / 65535.0);
    case DepthFormat::U8:
      return float(std::nearbyint(x * 255.0) / 255.0);
    case DepthFormat::U8Cubic: {
      const double k = std::nearbyint(std::cbrt(x) * 255.0) / 255.0;
      return float(k * k * k);
    }
    default:
      return d;
  }
}

void quantize_depths(float* d, size_t n, DepthFormat f) {
  if (f == DepthFormat::F32) return;
  parallel_for_chunks(n, 16384, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) d[i] = quantize_depth(d[i], f);
  });
}

}  // namespace shadowlab
