#include "techniques/filters/pcss/penumbra_model.h"

#include <algorithm>
#include <cmath>

namespace shadowlab {

PenumbraModel penumbra_model(double r_e, double z_f, double z_min, double z_max) {
  PenumbraModel m;
  m.z_m = 0.5 * (z_max + z_min);                                   // eq. 1
  m.r_s = 0.5 * (z_max - z_min);                                   // eq. 2
  const double am = std::sqrt(m.z_m * m.z_m + r_e * r_e);          // eq. 3
  m.theta_delta = std::asin(std::min(1.0, m.r_s / am));            // eq. 4
  const double bq = r_e * (z_f - m.z_m) / m.z_m;                   // eq. 5
  m.theta = std::atan((bq + r_e) / z_f);                           // eq. 6
  // A tangent ray at or past 90° from the axis never reaches the receiver plane.
  const double far = std::min(m.theta + m.theta_delta, 0.5 * M_PI - 1e-9);
  m.x_a = z_f * std::tan(m.theta - m.theta_delta) - r_e;           // eq. 7
  m.x_b = z_f * std::tan(far) - r_e;                               // eq. 8
  m.width = m.x_a + m.x_b;
  return m;
}

namespace {

// Does the segment from emitter point (ex, ey, 0) to the receiver point (x, 0, z_f) pass within
// r_s of the sphere's centre (0, 0, z_m)? (Depth along +z.)
bool sphere_blocks(double ex, double ey, double x, double z_f, double z_m, double r_s) {
  const double dx = x - ex, dy = -ey, dz = z_f;
  const double ox = ex, oy = ey, oz = -z_m;
  const double a = dx * dx + dy * dy + dz * dz, b = 2.0 * (ox * dx + oy * dy + oz * dz);
  const double c = ox * ox + oy * oy + oz * oz - r_s * r_s;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return false;
  const double t = (-b - std::sqrt(disc)) / (2.0 * a);
  return t > 0.0 && t < 1.0;
}

}  // namespace

double penumbra_lit_fraction(const PenumbraModel& m, double r_e, double z_f, double x) {
  if (r_e <= 0.0) return sphere_blocks(0.0, 0.0, x, z_f, m.z_m, m.r_s) ? 0.0 : 1.0;
  // Midpoints of kRings equal-area rings × kSpokes angles over the emitter disk; the half of the
  // disk with y < 0 mirrors the other (the receiver lies in the plane y = 0).
  constexpr int kRings = 160, kSpokes = 360;
  int lit = 0;
  for (int i = 0; i < kRings; ++i) {
    const double r = r_e * std::sqrt((i + 0.5) / kRings);
    for (int j = 0; j < kSpokes; ++j) {
      const double phi = M_PI * (j + 0.5) / kSpokes;
      lit += sphere_blocks(r * std::cos(phi), r * std::sin(phi), x, z_f, m.z_m, m.r_s) ? 0 : 1;
    }
  }
  return double(lit) / double(kRings * kSpokes);
}

namespace {

// The smallest x in [0, hi] with lit(x) >= level (lit increases with x), by bisection.
double crossing(const PenumbraModel& m, double r_e, double z_f, double level, double hi) {
  double lo = 0.0;
  for (int i = 0; i < 48; ++i) {
    const double mid = 0.5 * (lo + hi);
    (penumbra_lit_fraction(m, r_e, z_f, mid) >= level ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double disk_edge_1090_ratio() {
  // F(t) = 1/2 + (t·√(1 − t²) + asin t)/π: the share of a unit disk left of the line x = t.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double t = 0.5 * (lo + hi);
    (0.5 + (t * std::sqrt(1.0 - t * t) + std::asin(t)) / M_PI >= 0.9 ? hi : lo) = t;
  }
  return 0.5 * (lo + hi);
}

PenumbraTransition penumbra_transition(const PenumbraModel& m, double r_e, double z_f) {
  PenumbraTransition t;
  if (m.r_s <= 0.0) {
    // A thin occluder: the sphere has no size, and the model's width means an edge, whose lit
    // fraction under the disk emitter is the circular segment's share (disk_edge_1090_ratio).
    const double k = disk_edge_1090_ratio();
    t.x10 = m.x_b - 0.5 * m.width * (1.0 + k);
    t.x90 = m.x_b - 0.5 * m.width * (1.0 - k);
    t.width = k * m.width;
    return t;
  }
  t.minimum = penumbra_lit_fraction(m, r_e, z_f, 0.0);
  const double end = std::max(0.0, m.x_b) * (1.0 + 1e-9) + 1e-12;  // fully lit from x_b on
  t.x10 = crossing(m, r_e, z_f, t.minimum + 0.1 * (1.0 - t.minimum), end);
  t.x90 = crossing(m, r_e, z_f, t.minimum + 0.9 * (1.0 - t.minimum), end);
  t.width = t.x90 - t.x10;
  return t;
}

PenumbraTransition measured_transition(const double* x, const double* v, int n) {
  PenumbraTransition t;
  if (n < 2) return t;
  t.minimum = *std::min_element(v, v + n);
  const double l10 = t.minimum + 0.1 * (1.0 - t.minimum);
  const double l90 = t.minimum + 0.9 * (1.0 - t.minimum);
  // Crossings after the minimum (the shadowed side comes first).
  const int start = int(std::min_element(v, v + n) - v);
  auto cross = [&](double level, int from, double& at) {
    for (int i = std::max(from, start); i + 1 < n; ++i)
      if (v[i] < level && v[i + 1] >= level) {
        at = x[i] + (level - v[i]) / (v[i + 1] - v[i]) * (x[i + 1] - x[i]);
        return i;
      }
    return -1;
  };
  const int i10 = cross(l10, start, t.x10);
  if (i10 < 0 || cross(l90, i10, t.x90) < 0) return PenumbraTransition{0.0, 0.0, 0.0, t.minimum};
  t.width = t.x90 - t.x10;
  return t;
}

}  // namespace shadowlab
