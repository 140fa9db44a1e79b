// The front end's vertex transform (raster/vertex_transform.h): every table this CPU runs
// against the scalar one, every clip coordinate and every outcode bit for bit, and the outcodes
// against plane tests written out here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/isa.h"
#include "raster/clip.h"
#include "raster/vertex_transform.h"

namespace shadowlab {
namespace {

// Random matrices and vertices, with vertices on and near the frustum's planes (w = ±x), at
// the origin (w = 0 for a projection through it), huge, and non-finite.
TEST(VertexTransform, EveryTableGivesTheScalarBits) {
  for (const Isa isa : cpu_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(vertex_transform_kernels(isa).isa, std::min(isa, Isa::avx2));
    const TransformVerticesFn fast = vertex_transform_kernels(isa).transform;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    size_t codes_seen = 0, nonfinite = 0;
    uint32_t bits_seen = 0;
    for (int trial = 0; trial < 400; ++trial) {
      mat4 m;
      if (trial % 2 == 0) {
        m = glm::perspective(glm::radians(90.0f), 1.0f, 0.05f, 40.0f) *
            glm::lookAt(vec3(u(rng), u(rng), u(rng)), vec3(u(rng), u(rng), 2.0f),
                        vec3(0.0f, 1.0f, 0.0f));
      } else {
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) m[c][r] = 10.0f * u(rng);
      }
      const size_t n = size_t(trial % 37);  // tails of every length
      std::vector<vec3> pos(n);
      for (size_t i = 0; i < n; ++i) {
        const float s = std::pow(10.0f, float(int(i % 9) - 3));
        pos[i] = s * vec3(u(rng), u(rng), u(rng));
        if ((trial + i) % 13 == 0) pos[i][i % 3] = (i % 2) ? inf : nan;
        if ((trial + i) % 17 == 0) pos[i] = vec3(0.0f);
        if ((trial + i) % 19 == 0) pos[i] = vec3(3e38f, -3e38f, 3e38f);  // overflows to ±inf
      }
      std::vector<vec4> cf(n), cs(n);
      std::vector<uint32_t> kf(n, 0xDEADBEEF), ks(n, 0xDEADBEEF);
      const float gx = 1.0f + u(rng) * u(rng), gy = 33.0f;
      fast(m, pos.data(), n, gx, gy, cf.data(), kf.data());
      transform_vertices_scalar(m, pos.data(), n, gx, gy, cs.data(), ks.data());
      for (size_t i = 0; i < n; ++i) {
        ASSERT_EQ(0, std::memcmp(&cf[i], &cs[i], sizeof(vec4))) << "trial " << trial << " vertex " << i;
        ASSERT_EQ(kf[i], ks[i]) << "trial " << trial << " vertex " << i;
        bits_seen |= ks[i];
        codes_seen += ks[i] != 0;
        nonfinite += ks[i] == kOutNonFinite;
      }
  }
  // Every outcode bit occurred, and non-finite vertices too: the comparison saw each case.
  EXPECT_EQ(bits_seen, kOutFrustum | kOutGuard | kOutNonFinite);
  EXPECT_GT(nonfinite, 100u);
  EXPECT_GT(codes_seen, 1000u);
  }
}

// The outcodes of hand-placed clip positions against the planes' definitions (clip.h): the
// viewport is |x|, |y| <= w with z >= -w, the guard band |x| <= gx·w, |y| <= gy·w.
TEST(VertexTransform, OutcodesFollowThePlanes) {
  std::vector<TransformVerticesFn> forms = {transform_vertices_scalar};
  for (const Isa isa : cpu_isas()) forms.push_back(vertex_transform_kernels(isa).transform);
  const mat4 identity(1.0f);
  // 8 vertices, so the AVX2 form takes them in its vector loop, not its scalar tail.
  const std::vector<vec3> pos = {
      {0.5f, 0.5f, 0.0f},    // inside: w = 1
      {1.5f, 0.0f, 0.0f},    // beyond right (x > w), inside the guard band (gx = 2)
      {-2.5f, 0.0f, 0.0f},   // beyond left of both
      {0.0f, 1.0f, 0.0f},    // on top: inside (a distance of 0 is not beyond)
      {0.0f, -3.5f, 0.0f},   // beyond bottom of both (gy = 3)
      {0.0f, 0.0f, -1.5f},   // beyond near (z + w < 0): bits 0 and 5
      {0.0f, 0.0f, -1.0f},   // on near: inside
      {1.0f, -1.0f, 0.0f}};  // on right and bottom: inside
  const uint32_t want[] = {0,
                           1u << 1,
                           (1u << 2) | (1u << 7),
                           0,
                           (1u << 4) | (1u << 9),
                           (1u << 0) | (1u << 5),
                           0,
                           0};
  for (TransformVerticesFn f : forms) {
    if (!f) continue;
    std::vector<vec4> clip(pos.size());
    std::vector<uint32_t> code(pos.size());
    f(identity, pos.data(), pos.size(), 2.0f, 3.0f, clip.data(), code.data());
    for (size_t i = 0; i < pos.size(); ++i) {
      EXPECT_EQ(clip[i], vec4(pos[i], 1.0f)) << i;
      EXPECT_EQ(code[i], want[i]) << "vertex " << i;
    }
  }
}

}  // namespace
}  // namespace shadowlab
