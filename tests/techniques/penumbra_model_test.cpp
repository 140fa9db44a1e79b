// The penumbra-width model (techniques/filters/pcss/penumbra_model.h) against independent geometry in long
// double: the tangent rays of a disk emitter's rim to a sphere, and brute-force ray tests over
// the emitter disk in 3-D.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "techniques/filters/pcss/penumbra_model.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

using ld = long double;

// Does the segment from emitter point e = (ex, ey, 0) to receiver point (x, 0, zf) (depth along
// +z) come within rs of the sphere's centre (0, 0, zm)? By the segment's closest point to the
// centre (the library solves the ray–sphere quadratic instead).
bool sphere_blocks(ld ex, ld ey, ld x, ld zf, ld zm, ld rs) {
  const ld dx = x - ex, dy = -ey, dz = zf;
  const ld t = std::clamp(((0 - ex) * dx + (0 - ey) * dy + zm * dz) / (dx * dx + dy * dy + dz * dz), ld(0), ld(1));
  const ld px = ex + t * dx, py = ey + t * dy, pz = t * dz - zm;
  return px * px + py * py + pz * pz < rs * rs;
}

// Fraction of a polar grid over the emitter disk (equal-area rings) visible from x.
ld disk_lit_fraction_3d(ld re, ld x, ld zf, ld zm, ld rs, int rings = 400, int spokes = 800) {
  ld lit = 0;
  for (int i = 0; i < rings; ++i) {
    const ld r = re * std::sqrt((i + 0.5L) / rings);
    for (int j = 0; j < spokes; ++j) {
      const ld phi = 2 * M_PIl * (j + 0.5L) / spokes;
      lit += sphere_blocks(r * std::cos(phi), r * std::sin(phi), x, zf, zm, rs) ? 0 : 1;
    }
  }
  return lit / (ld(rings) * spokes);
}

struct ModelCase {
  double re, zf, zmin, zmax;
};
const ModelCase kModelCases[] = {{0.03, 3.0, 1.75, 2.25}, {0.1, 3.0, 1.75, 2.25}, {0.3, 3.0, 1.75, 2.25},
                       {0.2, 2.0, 0.9, 1.0}, {0.05, 4.0, 1.0, 3.0}};

// x_a and x_b are where A's tangent rays to the circle land (angles of the tangents from the
// direction A → M, intersected with the receiver line), computed here from vectors.
TEST(PenumbraModel, EndsAreWhereTheRimsTangentRaysLand) {
  for (const ModelCase& c : kModelCases) {
    const PenumbraModel m = penumbra_model(c.re, c.zf, c.zmin, c.zmax);
    const ld zm = (ld(c.zmin) + c.zmax) / 2, rs = (ld(c.zmax) - c.zmin) / 2;
    const ld ax = -ld(c.re);  // A, at depth 0; M = (0, zm)
    const ld to_m = std::atan2(0 - ax, zm), half = std::asin(rs / std::hypot(0 - ax, zm));
    const ld xa = ax + c.zf * std::tan(to_m - half), xb = ax + c.zf * std::tan(to_m + half);
    EXPECT_NEAR(m.x_a, double(xa), 1e-12 * c.zf);
    EXPECT_NEAR(m.x_b, double(xb), 1e-12 * c.zf);
    EXPECT_NEAR(m.width, double(xa + xb), 1e-12 * c.zf);
  }
}

// In 3-D, for a disk emitter facing the receiver and the sphere on its axis: just beyond x_b
// every emitter point is visible and just inside it one is not; just inside −x_a (an umbra)
// none is and just outside it one is.
TEST(PenumbraModel, EndsAreThePenumbrasExactEndsIn3D) {
  for (const ModelCase& c : kModelCases) {
    const PenumbraModel m = penumbra_model(c.re, c.zf, c.zmin, c.zmax);
    const ld zm = m.z_m, rs = m.r_s, eps = 1e-6L * c.zf;
    // Emitter points densely on the rim (the extremes lie there) and across the disk.
    auto any = [&](ld x, bool want_blocked) {
      for (int i = 0; i <= 40; ++i)
        for (int j = 0; j < 2000; ++j) {
          const ld r = c.re * i / 40.0L, phi = 2 * M_PIl * j / 2000.0L;
          if (sphere_blocks(r * std::cos(phi), r * std::sin(phi), x, c.zf, zm, rs) == want_blocked) return true;
        }
      return false;
    };
    EXPECT_FALSE(any(m.x_b + eps, true)) << "a point beyond x_b is shadowed";
    EXPECT_TRUE(any(m.x_b - 1e-3L * c.zf, true));
    if (m.x_a < 0) {
      EXPECT_FALSE(any(-m.x_a - eps, false)) << "a point inside the umbra sees the emitter";
      EXPECT_TRUE(any(-m.x_a + 1e-3L * c.zf, false));
    }
  }
}

// Small angles: the classic PCSS width 2·r_e·(z_f − z_m)/z_m; a point occluder (z_min = z_max)
// gives x_a = x_b.
TEST(PenumbraModel, SmallAnglesGiveTheClassicWidth) {
  const PenumbraModel m = penumbra_model(1e-4, 3.0, 2.0 - 1e-6, 2.0 + 1e-6);
  EXPECT_NEAR(m.width / (2 * 1e-4 * (3.0 - 2.0) / 2.0), 1.0, 1e-5);
  const PenumbraModel p = penumbra_model(0.1, 3.0, 2.0, 2.0);
  EXPECT_DOUBLE_EQ(p.x_a, p.x_b);
  EXPECT_NEAR(p.x_b, 0.1 * 1.0 / 2.0, 1e-15);  // BQ: the line from A through M
}

// The model's lit fraction (its grid over the half disk) against a finer brute force over the
// whole disk with another grid (240 rings × 500 angles), across the penumbra; and the 10–90 %
// width of the model's profile against the brute-force profile's.
TEST(PenumbraModel, ProfileMatchesThe3DBruteForce) {
  for (const ModelCase& c : {kModelCases[1], kModelCases[2]}) {
    const PenumbraModel m = penumbra_model(c.re, c.zf, c.zmin, c.zmax);
    double worst = 0.0;
    std::vector<double> xs, vs;
    const double x0 = std::max(0.0, -m.x_a) - 0.02, x1 = m.x_b + 0.02;
    for (int i = 0; i <= 24; ++i) {
      const double x = x0 + (x1 - x0) * i / 24.0;
      const double exact = double(disk_lit_fraction_3d(c.re, x, c.zf, m.z_m, m.r_s, 240, 500));
      worst = test::worst_of(worst, std::fabs(penumbra_lit_fraction(m, c.re, c.zf, x) - exact));
      xs.push_back(x);
      vs.push_back(exact);
    }
    std::printf("re %.2f: worst |model - 3-D| %.4f\n", c.re, worst);
    EXPECT_LT(worst, 0.002) << c.re;
    const PenumbraTransition model = penumbra_transition(m, c.re, c.zf);
    const PenumbraTransition brute = measured_transition(xs.data(), vs.data(), int(xs.size()));
    std::printf("re %.2f: 10-90 width model %.5f, brute force %.5f\n", c.re, model.width, brute.width);
    EXPECT_NEAR(model.width / brute.width, 1.0, 0.01) << c.re;
  }
}

// A thin occluder's transition is a straight edge's: the circular segment's 10 % and 90 %
// points, checked by integrating the unit disk's chord length 2·√(1 − x²) from −1 to the ratio
// (midpoint rule in long double on x = −cos θ, 200,000 steps).
TEST(PenumbraModel, ThinOccluderGivesTheDiskEdgeProfile) {
  const double k = disk_edge_1090_ratio();
  const int n = 200000;
  const ld theta_k = std::acos(-ld(k));  // x = −cos θ, dx = sin θ dθ
  ld area = 0;
  for (int i = 0; i < n; ++i) {
    const ld th = theta_k * (i + 0.5L) / n;
    area += 2 * std::sin(th) * std::sin(th) * theta_k / n;
  }
  EXPECT_NEAR(double(area / M_PIl), 0.9, 1e-9);
  const PenumbraModel m = penumbra_model(0.1, 3.0, 2.0, 2.0);
  const PenumbraTransition t = penumbra_transition(m, 0.1, 3.0);
  EXPECT_NEAR(t.width, k * m.width, 1e-15);
  EXPECT_NEAR(0.5 * (t.x10 + t.x90), m.x_b - 0.5 * m.width, 1e-15);  // centred on the edge
}

TEST(PenumbraModel, MeasuredTransitionOfARamp) {
  std::vector<double> x, v;
  for (int i = 0; i <= 40; ++i) {
    x.push_back(0.1 * i);
    v.push_back(std::clamp((0.1 * i - 1.0) / 2.0, 0.0, 1.0));
  }
  const PenumbraTransition t = measured_transition(x.data(), v.data(), int(x.size()));
  EXPECT_NEAR(t.x10, 1.2, 1e-12);
  EXPECT_NEAR(t.x90, 2.8, 1e-12);
  EXPECT_NEAR(t.width, 1.6, 1e-12);
  EXPECT_EQ(t.minimum, 0.0);
}

}  // namespace
}  // namespace shadowlab
