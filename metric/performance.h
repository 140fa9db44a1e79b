#pragma once
// Rendering-performance score (docs/design.md §5.7).

namespace shadowlab {

// Frame timings in milliseconds (medians of repeats, docs/design.md §4): the frame with the shadow
// technique, and the same frame without shadows; the shadow cost is their difference.
struct Timings {
  double shadowed_ms = 0.0;
  double unshadowed_ms = 0.0;
};

// RP = 1/(1 + (shadowed − unshadowed)/T_ref) with T_ref = 1000/target_fps ms (one frame at
// the target rate), clamped to [0, 1]: a difference below zero (timing noise) scores 1.
// Throws InputError for negative or non-finite times, or a target_fps that is not > 0.
double performance_score(const Timings& timings, double target_fps = 30.0);

}  // namespace shadowlab
