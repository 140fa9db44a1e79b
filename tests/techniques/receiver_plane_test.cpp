// Receiver-plane depth bias (rpdb): the plane gradient in a face's texel space against a finite
// difference of the exact distance to the receiver's plane, found by intersecting the rays
// through neighbouring texel coordinates with that plane (an independent computation).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "techniques/pipeline/light_faces.h"
#include "techniques/lookup/map_receiver.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Normalised distance from the light (at the origin) along the ray through st of face f to the
// plane through q with normal n, in double.
double plane_distance(const LightFace& f, double sx, double sy, const vec3& q, const vec3& n,
                      double inv_far) {
  const vec3 d = glm::normalize(face_texel_direction(f, float(sx), float(sy)));
  const double num = double(n.x) * q.x + double(n.y) * q.y + double(n.z) * q.z;
  const double den = double(n.x) * d.x + double(n.y) * d.y + double(n.z) * d.z;
  return num / den * inv_far;
}

// The largest relative error of grad(f, st, q, n, inv_far) against the central difference of
// the plane distance over ±h texels, at `trials` random receivers per face of each layout: texel
// coordinates in the middle `span` of the face, planes at least 30° from grazing (inside the
// gradients' cosine clamp). `checked` counts the receivers.
template <class Grad>
double worst_gradient_error(const std::vector<FaceLayout>& layouts, unsigned seed, int trials,
                            float span, double h, const Grad& grad, int& checked) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float lo = 0.5f * (1.0f - span);
  double worst = 0.0;
  checked = 0;
  for (const FaceLayout& L : layouts)
    for (const LightFace& f : L.faces)
      for (int trial = 0; trial < trials; ++trial) {
        const float sx = lo * float(f.width) + span * float(f.width) * (0.5f + 0.5f * u(rng));
        const float sy = lo * float(f.height) + span * float(f.height) * (0.5f + 0.5f * u(rng));
        const vec3 dir = glm::normalize(face_texel_direction(f, sx, sy));
        const vec3 q = dir * (1.0f + 2.0f * (0.5f + 0.5f * u(rng)));
        vec3 n = glm::normalize(vec3(u(rng), u(rng), u(rng)));
        if (glm::dot(n, dir) > 0.0f) n = -n;  // facing the light
        if (-glm::dot(n, dir) < 0.5f) continue;  // >= 30° from grazing
        const double inv_far = 1.0 / 20.0;
        const vec2 st = face_texel_coords(f, q);
        const vec2 g = grad(f, st, q, n, float(inv_far));
        const double gx = (plane_distance(f, st.x + h, st.y, q, n, inv_far) -
                           plane_distance(f, st.x - h, st.y, q, n, inv_far)) / (2 * h);
        const double gy = (plane_distance(f, st.x, st.y + h, q, n, inv_far) -
                           plane_distance(f, st.x, st.y - h, q, n, inv_far)) / (2 * h);
        const double scale = std::max(std::hypot(gx, gy), 1e-9);
        worst = test::worst_of(worst, std::hypot(g.x - gx, g.y - gy) / scale);
        ++checked;
      }
  return worst;
}

// On every cube and tetrahedral face the gradient equals the central difference over ±0.5
// texel. Measured worst relative error 5.4e-4 (float directions and the difference's own
// curvature term); bound 2e-3.
TEST(ReceiverPlane, GradientIsTheDerivativeOfThePlaneDistance) {
  int checked = 0;
  const double worst = worst_gradient_error(
      {cube_layout(256, 2), tetra_layout(256, 2)}, 5, 200, 0.6f, 0.5,
      [](const LightFace& f, vec2, const vec3& q, const vec3& n, float inv_far) {
        return receiver_plane_gradient(f, q, n, inv_far);
      },
      checked);
  RecordProperty("worst_relative_error", std::to_string(worst));
  EXPECT_GT(checked, 500);
  EXPECT_LT(worst, 2e-3);
}

// The paraboloid faces' gradient (central differences over ±½ texel of the plane distance)
// against the derivative of the plane distance, by a difference over ±0.1 texel, on both
// hemispheres' inner discs. The two differ by the ±½ difference's curvature term and float
// rounding: measured worst relative error 7.3e-4; bound 3e-3 (a one-sided half-texel
// difference is off by about a half).
TEST(ReceiverPlane, ParaboloidGradientIsTheDerivativeOfThePlaneDistance) {
  int checked = 0;
  const double worst = worst_gradient_error({dual_paraboloid_layout(256, 2)}, 7, 300, 0.4f, 0.1,
                                            receiver_plane_gradient_numeric, checked);
  RecordProperty("worst_relative_error", std::to_string(worst));
  EXPECT_GT(checked, 200);
  EXPECT_LT(worst, 3e-3);
}

}  // namespace
}  // namespace shadowlab
