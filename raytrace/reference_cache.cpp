#include "raytrace/reference_cache.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "core/cache_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"

namespace shadowlab {
namespace {

constexpr char kMagic[8] = {'S', 'L', 'R', 'E', 'F', 'M', 'K', '1'};
constexpr size_t kKeyLength = 16;
constexpr size_t kHeaderBytes = sizeof(kMagic) + kKeyLength + 4 * sizeof(uint32_t);

std::string hex16(uint64_t v) {
  return fmt::format("{:016x}", v);
}

bool valid_key(const std::string& key) {
  if (key.size() != kKeyLength) return false;
  for (char c : key)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

void put_u32(std::vector<char>& out, uint32_t v) {
  const char* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

uint32_t get_u32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

std::string reference_key(const Scene& scene, const GBuffer& gbuffer, int spp, uint64_t seed) {
  Fnv1a h;
  h.u64(kReferenceVersion);

  h.u64(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    h.u64(m.positions.size());
    for (const vec3& p : m.positions) h.v3(p);
    h.array(m.indices);
    h.u64(m.uvs.size());
    for (const vec2& uv : m.uvs) h.v2(uv);
    h.u64(uint64_t(int64_t(m.material)));
  }

  h.u64(scene.materials.size());
  for (const Material& mat : scene.materials) {
    h.u64(uint64_t(int64_t(mat.alpha_texture)));
    if (mat.alpha_texture < 0 || size_t(mat.alpha_texture) >= scene.textures.size()) continue;
    h.f32(mat.alpha_cutoff);
    const ImageF& tex = scene.textures[size_t(mat.alpha_texture)];
    h.u64(uint64_t(tex.width));
    h.u64(uint64_t(tex.height));
    h.u64(uint64_t(tex.channels));
    // Only the alpha plane (channel 3 of RGBA) can change the mask.
    if (tex.channels == 4 && !tex.empty() && tex.data.size() == 4 * tex.pixel_count())
      h.bytes(tex.plane(3), tex.pixel_count() * sizeof(float));
  }

  h.v3(scene.light.position);
  h.f32(scene.light.radius);
  // A point light ignores spp and seed: hash fixed values so hard references are shared.
  const bool hard = !(scene.light.radius > 0.0f);
  h.u64(hard ? 1 : uint64_t(int64_t(spp)));
  h.u64(hard ? 0 : seed);

  h.u64(uint64_t(gbuffer.width));
  h.u64(uint64_t(gbuffer.height));
  const size_t n = gbuffer.pixel_count();
  SL_CHECK_EQ(gbuffer.covered.size(), n);
  SL_CHECK_EQ(gbuffer.position.size(), n);
  SL_CHECK_EQ(gbuffer.geo_normal.size(), n);
  for (size_t p = 0; p < n; ++p) {
    const uint8_t c = gbuffer.covered[p] ? 1 : 0;
    h.bytes(&c, 1);
    if (!c) continue;  // values in empty pixels are meaningless
    h.v3(gbuffer.position[p]);
    h.v3(gbuffer.geo_normal[p]);
  }
  return hex16(h.h);
}

std::string default_cache_dir() {
  if (const char* env = std::getenv("SHADOWLAB_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && xdg[0] == '/')
    return std::string(xdg) + "/shadowlab";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.cache/shadowlab";
  return "";
}

std::string cached_reference_path(const std::string& dir, const std::string& key) {
  return (std::filesystem::path(dir) / (key + ".slref")).string();
}

bool load_cached_reference(const std::string& dir, const std::string& key, ImageF& out) {
  if (dir.empty() || !valid_key(key)) return false;
  const std::string path = cached_reference_path(dir, key);
  std::vector<char> buf;
  if (!read_file_bytes(path, kHeaderBytes + sizeof(uint64_t), buf)) return false;
  const size_t size = buf.size();

  // Header.
  if (std::memcmp(buf.data(), kMagic, sizeof kMagic) != 0) return false;
  if (std::memcmp(buf.data() + sizeof kMagic, key.data(), kKeyLength) != 0) return false;
  const char* q = buf.data() + sizeof kMagic + kKeyLength;
  const uint32_t version = get_u32(q), w = get_u32(q + 4), hgt = get_u32(q + 8),
                 ch = get_u32(q + 12);
  if (version != kReferenceVersion) return false;
  if (w > uint32_t(kMaxImageSide) || hgt > uint32_t(kMaxImageSide) || ch < 1 || ch > 4)
    return false;
  const size_t count = size_t(w) * size_t(hgt) * size_t(ch);
  if (size_t(size) != kHeaderBytes + count * sizeof(float) + sizeof(uint64_t)) return false;

  // Checksum over everything before it.
  const size_t body = size_t(size) - sizeof(uint64_t);
  Fnv1a h;
  h.bytes(buf.data(), body);
  uint64_t stored;
  std::memcpy(&stored, buf.data() + body, sizeof stored);
  if (stored != h.h) return false;

  ImageF img(static_cast<int>(w), static_cast<int>(hgt), static_cast<int>(ch));
  if (count) std::memcpy(img.data.data(), buf.data() + kHeaderBytes, count * sizeof(float));
  for (float v : img.data)
    if (!(v >= 0.0f && v <= 1.0f)) return false;  // also rejects NaN
  out = std::move(img);
  return true;
}

void store_cached_reference(const std::string& dir, const std::string& key, const ImageF& mask) {
  if (dir.empty()) return;
  if (!valid_key(key)) throw InputError(dir, "invalid reference cache key '" + key + "'");
  SL_CHECK_EQ(mask.data.size(), mask.pixel_count() * size_t(mask.channels));

  // Constructed from the magic, not inserted into an empty vector: GCC 12 warns falsely
  // (-Wstringop-overflow) on that insert once it is inlined here.
  std::vector<char> buf(kMagic, kMagic + sizeof kMagic);
  buf.reserve(kHeaderBytes + mask.data.size() * sizeof(float) + sizeof(uint64_t));
  buf.insert(buf.end(), key.begin(), key.end());
  put_u32(buf, kReferenceVersion);
  put_u32(buf, uint32_t(mask.width));
  put_u32(buf, uint32_t(mask.height));
  put_u32(buf, uint32_t(mask.channels));
  const char* data = reinterpret_cast<const char*>(mask.data.data());
  buf.insert(buf.end(), data, data + mask.data.size() * sizeof(float));
  Fnv1a h;
  h.bytes(buf.data(), buf.size());
  const char* sum = reinterpret_cast<const char*>(&h.h);
  buf.insert(buf.end(), sum, sum + sizeof h.h);

  write_file_atomically(dir, cached_reference_path(dir, key), buf, "reference cache file");
}

ImageF cached_reference_mask(const Scene& scene, const GBuffer& gbuffer, int spp, uint64_t seed,
                             const std::string& dir, bool* from_cache) {
  const std::string key = reference_key(scene, gbuffer, spp, seed);
  ImageF mask;
  if (load_cached_reference(dir, key, mask) && mask.width == gbuffer.width &&
      mask.height == gbuffer.height && mask.channels == 1) {
    if (from_cache) *from_cache = true;
    return mask;
  }
  if (from_cache) *from_cache = false;
  const EmbreeScene rt(scene);
  mask = soft_visibility(rt, scene, gbuffer, spp, seed);
  try {
    store_cached_reference(dir, key, mask);
  } catch (const InputError& e) {
    std::fprintf(stderr, "warning: reference not cached: %s\n", e.what());
  }
  return mask;
}

}  // namespace shadowlab
