// rasterize_frame's tile-local path (raster/rasterize_tile.h): depth-only shaders on a cleared
// target without ids draw each tile into a 16 KB buffer and stream it into the target. It must
// give the bits of the in-place path (taken for targets that keep ids), with and without a tile
// epilogue, on whole and partial tiles.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/parallel.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

// A tile epilogue whose result depends on the pixel's position, so an epilogue that addressed
// the wrong pixel of the tile buffer would show.
struct PositionalEpilogue {
  static constexpr bool kNeedsAttributes = false;
  static constexpr bool kKeepsAll = true;
  bool operator()(const Fragment&) const { return true; }
  void finish_tile(int x0, int y0, int x1, int y1, float* z, size_t stride) const {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        float& v = z[size_t(y) * stride + size_t(x)];
        v = v * 0.5f + float(x) + 1000.0f * float(y);
      }
  }
};

// 4,000 random triangles in front of a 90° perspective camera (some crossing the near plane).
std::vector<vec3> random_soup() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> xy(-6.0f, 6.0f), z(-8.0f, 0.5f), d(-1.5f, 1.5f);
  std::vector<vec3> p;
  for (int t = 0; t < 4000; ++t) {
    const vec3 c(xy(rng), xy(rng), z(rng));
    for (int k = 0; k < 3; ++k) p.push_back(c + vec3(d(rng), d(rng), d(rng)));
  }
  return p;
}

template <class Shader>
void expect_local_equals_in_place(int w, int h) {
  const std::vector<vec3> pos = random_soup();
  std::vector<uint32_t> idx(pos.size());
  for (uint32_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const std::vector<MeshView> views = {{pos.data(), pos.size(), idx.data(), idx.size() / 3}};
  const mat4 vp = glm::perspectiveRH_NO(glm::radians(90.0f), float(w) / float(h), 0.1f, 100.0f);
  for (const int threads : {1, 2, 7}) {
    set_thread_count(threads);
    DepthTarget local, in_place;
    in_place.with_ids = true;  // ids keep the in-place path
    Shader a, b;
    rasterize(views, vp, CullMode::None, w, h, local, a);
    rasterize(views, vp, CullMode::None, w, h, in_place, b);
    // The conditions under which rasterize_frame takes the tile-local path.
    ASSERT_EQ(w % 16, 0);
    ASSERT_GE(size_t(w) * size_t(h) * sizeof(float), kStreamedTargetBytes);
    ASSERT_EQ(reinterpret_cast<uintptr_t>(local.inv_w.data()) % 64, 0u);
    ASSERT_EQ(local.inv_w.size(), in_place.inv_w.size());
    size_t covered = 0;
    for (const float v : in_place.inv_w) covered += v != 0.0f;
    EXPECT_GT(covered, size_t(w) * size_t(h) / 10) << "too few covered pixels to mean much";
    EXPECT_EQ(0, std::memcmp(local.inv_w.data(), in_place.inv_w.data(),
                             local.inv_w.size() * sizeof(float)))
        << w << "x" << h << ", " << threads << " threads";
  }
  set_thread_count(2);
}

TEST(TileLocal, DepthEqualsTheInPlacePathBitForBit) {
  expect_local_equals_in_place<DepthOnlyShader>(2048, 1024);  // whole 64 x 64 tiles
  expect_local_equals_in_place<DepthOnlyShader>(2064, 1040);  // partial tiles, 16 wide and high
}

TEST(TileLocal, TileEpilogueSeesEveryPixelAtItsOwnPosition) {
  expect_local_equals_in_place<PositionalEpilogue>(2048, 1024);
  expect_local_equals_in_place<PositionalEpilogue>(2064, 1040);
}

}  // namespace
}  // namespace shadowlab
