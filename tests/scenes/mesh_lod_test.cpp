#include "scenes/mesh_lod.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/obj_loader.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

// The Stanford bunny (69,451 triangles), loaded once; empty if it is not one mesh.
const Mesh& bunny() {
  static const Mesh mesh = [] {
    const std::string path = test::assets_dir() + "/bunny/stanford-bunny.obj";
    std::vector<std::string> notes;  // recomputed normals: expected, not printed
    Scene scene = load_obj_scene(path, &notes);
    return scene.meshes.size() == 1 ? scene.meshes[0] : Mesh{};
  }();
  return mesh;
}

Bounds mesh_bounds(const Mesh& m) {
  Bounds b;
  for (const vec3& p : m.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

// Scratch cache folder, emptied so that the first call always computes.
std::string fresh_cache_dir(const std::string& name) {
  const std::string dir = test::binary_path("core/lod_cache/" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

bool same_arrays(const Mesh& a, const Mesh& b) {
  return a.positions == b.positions && a.normals == b.normals && a.uvs == b.uvs &&
         a.indices == b.indices;
}

// The slide-projector levels: the issue accepts ±5 % of the target.
TEST(MeshLod, BunnyLevelsAreWithinFivePercentAndWellFormed) {
  const Mesh& full = bunny();
  ASSERT_FALSE(full.indices.empty());
  ASSERT_EQ(full.triangle_count(), 69451u);
  const Bounds fb = mesh_bounds(full);
  const float diagonal = glm::length(fb.extent());

  for (size_t target : {5000u, 1000u, 300u}) {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh lod = simplify_mesh(full, target);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ bunny LOD ] target %zu: %zu triangles, %zu vertices, %.1f ms\n", target,
                lod.triangle_count(), lod.positions.size(), ms);

    const double ratio = double(lod.triangle_count()) / double(target);
    EXPECT_NEAR(ratio, 1.0, 0.05) << "target " << target << " got " << lod.triangle_count();
    EXPECT_EQ(lod.name, full.name);
    EXPECT_EQ(lod.material, full.material);
    EXPECT_TRUE(lod.uvs.empty());  // the bunny has none
    ASSERT_EQ(lod.normals.size(), lod.positions.size()) << "target " << target;
    for (size_t v = 0; v < lod.normals.size(); ++v)
      ASSERT_NEAR(glm::length(lod.normals[v]), 1.0f, 1e-4f) << "target " << target << " v " << v;
    ASSERT_EQ(lod.indices.size() % 3, 0u);
    for (size_t t = 0; t < lod.indices.size(); t += 3) {
      const uint32_t a = lod.indices[t], b = lod.indices[t + 1], c = lod.indices[t + 2];
      ASSERT_LT(a, lod.positions.size());
      ASSERT_LT(b, lod.positions.size());
      ASSERT_LT(c, lod.positions.size());
      ASSERT_TRUE(a != b && b != c && c != a) << "degenerate triangle " << t / 3;
      const vec3 n = glm::cross(lod.positions[b] - lod.positions[a],
                                lod.positions[c] - lod.positions[a]);
      ASSERT_GT(glm::length(n), 0.0f) << "zero-area triangle " << t / 3;
    }
    // Collapses move vertices onto kept ones: the box may shrink a little, never grow much.
    const Bounds lb = mesh_bounds(lod);
    EXPECT_LE(glm::length(lb.lo - fb.lo), 0.02f * diagonal) << "target " << target;
    EXPECT_LE(glm::length(lb.hi - fb.hi), 0.02f * diagonal) << "target " << target;
  }
}

// Same input, same bits: the cache relies on it, and so do the experiment's timings.
TEST(MeshLod, IsDeterministic) {
  const Mesh& full = bunny();
  ASSERT_FALSE(full.indices.empty());
  EXPECT_TRUE(same_arrays(simplify_mesh(full, 1000), simplify_mesh(full, 1000)));
}

TEST(MeshLod, CacheReturnsTheSameMeshAndSurvivesCorruption) {
  const Mesh& full = bunny();
  ASSERT_FALSE(full.indices.empty());
  const std::string dir = fresh_cache_dir("bunny");

  bool cached = true;
  const Mesh first = simplify_mesh_cached(full, 1000, dir, &cached);
  EXPECT_FALSE(cached);
  const std::string path = mesh_lod_cache_path(dir, mesh_lod_key(full, 1000));
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  EXPECT_TRUE(same_arrays(first, simplify_mesh(full, 1000)));

  const Mesh second = simplify_mesh_cached(full, 1000, dir, &cached);
  EXPECT_TRUE(cached);
  EXPECT_TRUE(same_arrays(first, second));
  EXPECT_EQ(second.name, full.name);
  EXPECT_EQ(second.material, full.material);

  // A truncated file is recomputed (and rewritten), never trusted.
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  const Mesh third = simplify_mesh_cached(full, 1000, dir, &cached);
  EXPECT_FALSE(cached);
  EXPECT_TRUE(same_arrays(first, third));
  EXPECT_EQ(std::filesystem::file_size(path), size);

  // Another target is another key.
  EXPECT_NE(mesh_lod_key(full, 1000), mesh_lod_key(full, 300));
}

// A small grid stands in for the bunny where only the rules are tested.
Mesh grid_mesh(int n) {
  Mesh m;
  m.name = "grid";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      m.positions.push_back(vec3(float(x), float(y), 0.0f));
      m.uvs.push_back(vec2(float(x) / float(n), float(y) / float(n)));
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1),
                     d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  return m;
}

TEST(MeshLod, ZeroTargetIsAnInputError) {
  const Mesh m = grid_mesh(4);
  try {
    simplify_mesh(m, 0, "--lod");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "--lod");
  }
  EXPECT_THROW(simplify_mesh_cached(m, 0, fresh_cache_dir("zero")), InputError);
}

TEST(MeshLod, GarbageInputIsAnInputError) {
  Mesh m = grid_mesh(4);
  m.indices.push_back(0);  // not a multiple of 3
  EXPECT_THROW(simplify_mesh(m, 4), InputError);
  m = grid_mesh(4);
  m.indices[5] = 1000;  // out of range
  EXPECT_THROW(simplify_mesh(m, 4), InputError);
  m = grid_mesh(4);
  m.positions[3].y = std::nanf("");
  EXPECT_THROW(simplify_mesh(m, 4), InputError);
}

// A target at or above the current count changes nothing (normals are not recomputed).
TEST(MeshLod, TargetAboveCountReturnsACopy) {
  Mesh m = grid_mesh(4);
  m.normals.assign(m.positions.size(), vec3(0.0f, 0.0f, 1.0f));
  bool cached = true;
  const Mesh same = simplify_mesh_cached(m, m.triangle_count(), fresh_cache_dir("copy"), &cached);
  EXPECT_FALSE(cached);
  EXPECT_TRUE(same_arrays(m, same));
  EXPECT_TRUE(same_arrays(m, simplify_mesh(m, 1000000)));
}

// A flat grid simplifies to a flat mesh with +z normals; unsplit uvs are kept.
TEST(MeshLod, FlatGridKeepsUvsAndPlaneNormals) {
  const Mesh m = grid_mesh(16);  // 512 triangles
  const Mesh lod = simplify_mesh(m, 64);
  EXPECT_LE(lod.triangle_count(), 64u * 21 / 20);
  ASSERT_EQ(lod.uvs.size(), lod.positions.size());
  for (size_t v = 0; v < lod.positions.size(); ++v) {
    // uv = position / 16 on this grid, so a kept vertex keeps its own uv.
    EXPECT_EQ(lod.uvs[v].x * 16.0f, lod.positions[v].x);
    EXPECT_NEAR(lod.normals[v].z, 1.0f, 1e-6f);
  }
}

// Corner-split input (every triangle with its own three vertices, as a per-face OBJ) is welded
// first: it simplifies as far as the connected grid, and conflicting uvs are dropped.
TEST(MeshLod, SplitCornersAreWelded) {
  const Mesh grid = grid_mesh(16);
  Mesh split;
  for (size_t i = 0; i < grid.indices.size(); ++i) {
    split.positions.push_back(grid.positions[grid.indices[i]]);
    // A uv seam: per-corner uvs that disagree between neighbours.
    split.uvs.push_back(vec2(float(i % 3), 0.0f));
    split.indices.push_back(uint32_t(i));
  }
  const Mesh lod = simplify_mesh(split, 64);
  EXPECT_LE(lod.triangle_count(), 64u * 21 / 20);
  EXPECT_TRUE(lod.uvs.empty());
  EXPECT_LE(lod.positions.size(), grid.positions.size());
}

// Every grid triangle three times over: each edge is shared by 3+ triangles, which stops the
// edge collapses far above the target, so the grid-clustering fallback must finish the job
// (it never exceeds the target, though it may undershoot).
TEST(MeshLod, NonManifoldInputFallsBackToSloppy) {
  const Mesh grid = grid_mesh(20);  // 800 triangles
  Mesh m = grid;
  for (int k = 0; k < 2; ++k)
    m.indices.insert(m.indices.end(), grid.indices.begin(), grid.indices.end());
  for (size_t target : {50u, 300u}) {
    const Mesh lod = simplify_mesh(m, target);
    EXPECT_LE(lod.triangle_count(), target * 21 / 20) << "target " << target;
    EXPECT_GT(lod.triangle_count(), 0u) << "target " << target;
    ASSERT_EQ(lod.normals.size(), lod.positions.size());
    for (uint32_t i : lod.indices) ASSERT_LT(i, lod.positions.size());
  }
}

}  // namespace
}  // namespace shadowlab
