#include "metric/performance.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/error.h"

namespace shadowlab {
namespace {

TEST(Performance, HandValues) {
  // A whole frame at 30 fps (33.33 ms) of shadow work halves the score.
  EXPECT_NEAR(performance_score({10.0 + 1000.0 / 30.0, 10.0}), 0.5, 1e-12);
  // Three frames' worth → 1/(1 + 3) = 0.25.
  EXPECT_NEAR(performance_score({100.0, 0.0}, 30.0), 0.25, 1e-12);
  // At 60 fps, T_ref = 16.67 ms.
  EXPECT_NEAR(performance_score({1000.0 / 60.0, 0.0}, 60.0), 0.5, 1e-12);
  // 5 ms at 50 fps (T_ref 20 ms) → 1/1.25 = 0.8.
  EXPECT_NEAR(performance_score({7.0, 2.0}, 50.0), 0.8, 1e-12);
  EXPECT_EQ(performance_score({4.0, 4.0}), 1.0);  // free shadows
  EXPECT_EQ(performance_score({3.0, 4.0}), 1.0);  // timing noise below zero: capped at 1
  // Any difference below zero scores 1, also one larger than a frame (the formula alone would
  // give a negative score there, clamped to 0).
  EXPECT_EQ(performance_score({1.0, 100.0}), 1.0);
}

TEST(Performance, BadTimingsThrow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(performance_score({-1.0, 0.0}), InputError);
  EXPECT_THROW(performance_score({1.0, nan}), InputError);
  EXPECT_THROW(performance_score({1.0, 0.0}, 0.0), InputError);
  EXPECT_THROW(performance_score({1.0, 0.0}, -30.0), InputError);
}

}  // namespace
}  // namespace shadowlab
