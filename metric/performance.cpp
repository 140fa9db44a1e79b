#include "metric/performance.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace shadowlab {

double performance_score(const Timings& t, double target_fps) {
  if (!(std::isfinite(t.shadowed_ms) && t.shadowed_ms >= 0.0 && std::isfinite(t.unshadowed_ms) &&
        t.unshadowed_ms >= 0.0))
    throw InputError("metric", "timings must be finite and >= 0 ms, got shadowed " +
                                   std::to_string(t.shadowed_ms) + " ms, unshadowed " +
                                   std::to_string(t.unshadowed_ms) + " ms");
  if (!(std::isfinite(target_fps) && target_fps > 0.0))
    throw InputError("metric", "target frame rate must be > 0, got " + std::to_string(target_fps));
  const double shadow_ms = t.shadowed_ms - t.unshadowed_ms;
  if (shadow_ms <= 0.0) return 1.0;  // free, or faster than the unshadowed frame: noise
  const double t_ref_ms = 1000.0 / target_fps;
  return std::clamp(1.0 / (1.0 + shadow_ms / t_ref_ms), 0.0, 1.0);
}

}  // namespace shadowlab
