// Reference cache: keys, on-disk format checks and atomic writes.
#include "raytrace/reference_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "../test_paths.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

// Floor + one occluder + alpha-tested card, a sphere light, and a 12 × 8 GBuffer on the floor.
struct Fixture {
  Scene scene;
  GBuffer gbuffer;
};

Fixture make_fixture() {
  Fixture f;
  Scene& s = f.scene;
  s.materials.push_back(Material{});
  Material leaf;
  leaf.alpha_texture = 0;
  leaf.alpha_cutoff = 0.5f;
  s.materials.push_back(leaf);
  ImageF tex(2, 2, 4, 1.0f);
  tex.at(0, 0, 3) = 0.0f;
  s.textures.push_back(tex);
  auto quad = [&](float y, float h, int material) {
    Mesh m;
    m.positions = {vec3(-h, y, h), vec3(h, y, h), vec3(h, y, -h), vec3(-h, y, -h)};
    m.uvs = {vec2(0, 1), vec2(1, 1), vec2(1, 0), vec2(0, 0)};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.material = material;
    compute_vertex_normals(m);
    s.meshes.push_back(m);
  };
  quad(0.0f, 10.0f, 0);
  quad(1.5f, 0.6f, 0);
  quad(2.5f, 1.0f, 1);
  s.light.position = vec3(0.3f, 4.0f, 0.1f);
  s.light.radius = 0.4f;
  f.gbuffer.resize(12, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x) {
      const size_t i = size_t(y) * 12 + x;
      f.gbuffer.position[i] = vec3(-1.5f + 0.25f * x, 0.0f, -1.0f + 0.25f * y);
      f.gbuffer.geo_normal[i] = vec3(0, 1, 0);
      f.gbuffer.normal[i] = vec3(0, 1, 0);
      f.gbuffer.covered[i] = (x + y) % 5 != 0;
    }
  return f;
}

// A fresh scratch folder for one test, removed again at its end.
struct ScratchDir {
  std::string path;
  explicit ScratchDir(const std::string& name)
      : path(test::binary_path("raytrace_cache_test/" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

ImageF test_mask(int w, int h) {
  ImageF m(w, h, 1, 0.0f);
  for (size_t i = 0; i < m.data.size(); ++i) m.data[i] = float(i % 17) / 16.0f;
  return m;
}

TEST(ReferenceKey, IsSixteenHexDigitsAndStable) {
  const Fixture f = make_fixture();
  const std::string k = reference_key(f.scene, f.gbuffer, 64, 7);
  ASSERT_EQ(k.size(), 16u);
  for (char c : k) EXPECT_TRUE((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f')) << k;
  EXPECT_EQ(k, reference_key(make_fixture().scene, make_fixture().gbuffer, 64, 7));
}

TEST(ReferenceKey, ChangesWithEverythingThatDeterminesTheMask) {
  const Fixture base = make_fixture();
  const std::string k0 = reference_key(base.scene, base.gbuffer, 64, 7);
  EXPECT_NE(k0, reference_key(base.scene, base.gbuffer, 65, 7)) << "spp";
  EXPECT_NE(k0, reference_key(base.scene, base.gbuffer, 64, 8)) << "seed";
  auto changed = [&](auto&& edit) {
    Fixture f = make_fixture();
    edit(f);
    return reference_key(f.scene, f.gbuffer, 64, 7);
  };
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.meshes[1].positions[2].x += 1e-3f; })) << "vertex";
  EXPECT_NE(k0, changed([](Fixture& f) { std::swap(f.scene.meshes[1].indices[0], f.scene.meshes[1].indices[1]); }))
      << "index";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.meshes[2].uvs[0].x = 0.1f; })) << "uv";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.materials[1].alpha_cutoff = 0.4f; })) << "cutoff";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.textures[0].at(1, 1, 3) = 0.2f; })) << "alpha";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.meshes[1].material = 1; })) << "material";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.light.position.y = 4.01f; })) << "light";
  EXPECT_NE(k0, changed([](Fixture& f) { f.scene.light.radius = 0.41f; })) << "radius";
  EXPECT_NE(k0, changed([](Fixture& f) { f.gbuffer.position[3].z += 1e-4f; })) << "position";
  EXPECT_NE(k0, changed([](Fixture& f) { f.gbuffer.geo_normal[3] = vec3(0, 0, 1); })) << "normal";
  EXPECT_NE(k0, changed([](Fixture& f) { f.gbuffer.covered[3] = 0; })) << "covered";

  // Things that cannot change the mask leave the key alone.
  EXPECT_EQ(k0, changed([](Fixture& f) { f.scene.materials[0].albedo = vec3(0.1f); }));
  EXPECT_EQ(k0, changed([](Fixture& f) { f.scene.textures[0].at(1, 1, 0) = 0.2f; }));  // red
  EXPECT_EQ(k0, changed([](Fixture& f) { f.gbuffer.position[0] = vec3(9.0f); }));  // uncovered
  EXPECT_EQ(k0, changed([](Fixture& f) { f.scene.camera.fov_y_deg = 30.0f; }));

  // A point light ignores spp and seed.
  Fixture hard = make_fixture();
  hard.scene.light.radius = 0.0f;
  EXPECT_EQ(reference_key(hard.scene, hard.gbuffer, 1, 0),
            reference_key(hard.scene, hard.gbuffer, 64, 99));
}

TEST(ReferenceCache, RoundTripIsBitExact) {
  const ScratchDir scratch("roundtrip");
  const std::string& dir = scratch.path;
  const std::string key = "0123456789abcdef";
  ImageF out;
  EXPECT_FALSE(load_cached_reference(dir, key, out));  // missing folder
  const ImageF mask = test_mask(13, 7);
  store_cached_reference(dir, key, mask);
  ASSERT_TRUE(load_cached_reference(dir, key, out));
  EXPECT_EQ(out.width, 13);
  EXPECT_EQ(out.height, 7);
  EXPECT_EQ(out.channels, 1);
  ASSERT_EQ(out.data.size(), mask.data.size());
  EXPECT_EQ(0, std::memcmp(out.data.data(), mask.data.data(), mask.data.size() * sizeof(float)));
  // No temporary file is left behind.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().extension(), ".slref");
  }
  EXPECT_EQ(files, 1);
  // Overwriting works too.
  store_cached_reference(dir, key, test_mask(2, 2));
  ASSERT_TRUE(load_cached_reference(dir, key, out));
  EXPECT_EQ(out.width, 2);
}

TEST(ReferenceCache, DamagedFilesAreRejected) {
  const ScratchDir scratch("damaged");
  const std::string& dir = scratch.path;
  const std::string key = "00000000deadbeef";
  const ImageF mask = test_mask(9, 5);
  store_cached_reference(dir, key, mask);
  const std::string path = cached_reference_path(dir, key);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto write = [&](const std::string& b) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(b.data(), std::streamsize(b.size()));
  };
  const ImageF sentinel = test_mask(1, 1);
  auto rejected = [&]() {
    ImageF out = sentinel;
    const bool ok = load_cached_reference(dir, key, out);
    return !ok && out.width == 1;  // untouched on failure
  };
  write(bytes.substr(0, bytes.size() - 1));
  EXPECT_TRUE(rejected()) << "truncated by one byte";
  write(bytes.substr(0, bytes.size() / 2));
  EXPECT_TRUE(rejected()) << "truncated to half";
  write(bytes.substr(0, 10));
  EXPECT_TRUE(rejected()) << "header only";
  write("");
  EXPECT_TRUE(rejected()) << "empty";
  write(bytes + "x");
  EXPECT_TRUE(rejected()) << "trailing garbage";
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  write(flipped);
  EXPECT_TRUE(rejected()) << "flipped data bit";
  write(bytes);
  ImageF ok;
  EXPECT_TRUE(load_cached_reference(dir, key, ok)) << "intact again";
  // The same bytes under another key's name are not trusted either.
  fs::copy_file(path, cached_reference_path(dir, "1111111111111111"));
  EXPECT_FALSE(load_cached_reference(dir, "1111111111111111", ok));
  // Keys that are not 16 hex digits are never used as file names.
  EXPECT_FALSE(load_cached_reference(dir, "../evil", ok));
  EXPECT_THROW(store_cached_reference(dir, "../evil", mask), InputError);
}

TEST(ReferenceCache, ComputesOnceThenLoads) {
  const ScratchDir scratch("compute");
  const std::string& dir = scratch.path;
  const Fixture f = make_fixture();
  bool cached = true;
  const ImageF first = cached_reference_mask(f.scene, f.gbuffer, 16, 3, dir, &cached);
  EXPECT_FALSE(cached);
  const ImageF second = cached_reference_mask(f.scene, f.gbuffer, 16, 3, dir, &cached);
  EXPECT_TRUE(cached);
  ASSERT_EQ(first.data.size(), second.data.size());
  EXPECT_EQ(0, std::memcmp(first.data.data(), second.data.data(), first.data.size() * sizeof(float)));
  // Truncating the file forces a recomputation that gives the same mask again.
  const std::string path = cached_reference_path(dir, reference_key(f.scene, f.gbuffer, 16, 3));
  fs::resize_file(path, fs::file_size(path) - 8);
  const ImageF third = cached_reference_mask(f.scene, f.gbuffer, 16, 3, dir, &cached);
  EXPECT_FALSE(cached);
  EXPECT_EQ(0, std::memcmp(first.data.data(), third.data.data(), first.data.size() * sizeof(float)));
  // Empty dir: caching disabled, still computed.
  cached = true;
  cached_reference_mask(f.scene, f.gbuffer, 16, 3, "", &cached);
  EXPECT_FALSE(cached);
}

// Sets an environment variable for the scope of a test and restores it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(ReferenceCache, DefaultDirFollowsTheEnvironment) {
  {
    ScopedEnv a("SHADOWLAB_CACHE", "/tmp/sl_cache");
    ScopedEnv b("XDG_CACHE_HOME", "/tmp/xdg");
    EXPECT_EQ(default_cache_dir(), "/tmp/sl_cache");
  }
  {
    ScopedEnv a("SHADOWLAB_CACHE", "");
    ScopedEnv b("XDG_CACHE_HOME", "/tmp/xdg");
    EXPECT_EQ(default_cache_dir(), "/tmp/xdg/shadowlab");
  }
  {
    ScopedEnv a("SHADOWLAB_CACHE", nullptr);
    ScopedEnv b("XDG_CACHE_HOME", "relative/ignored");
    ScopedEnv c("HOME", "/home/someone");
    EXPECT_EQ(default_cache_dir(), "/home/someone/.cache/shadowlab");
  }
  {
    ScopedEnv a("SHADOWLAB_CACHE", nullptr);
    ScopedEnv b("XDG_CACHE_HOME", nullptr);
    ScopedEnv c("HOME", nullptr);
    EXPECT_EQ(default_cache_dir(), "");
  }
}

}  // namespace
}  // namespace shadowlab
