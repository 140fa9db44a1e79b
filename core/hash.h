#pragma once
// FNV-1a 64-bit hashing of raw bytes, for cache keys and file checksums (the reference cache,
// the LOD cache). Hashes the native (little-endian) bytes, so keys are per machine kind.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace shadowlab {

struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ull;
    }
  }
  void u64(uint64_t v) { bytes(&v, sizeof v); }
  void f32(float v) { bytes(&v, sizeof v); }
  void v2(const vec2& v) {
    f32(v.x);
    f32(v.y);
  }
  void v3(const vec3& v) {
    f32(v.x);
    f32(v.y);
    f32(v.z);
  }
  // Sized arrays: the length goes first so that concatenations cannot collide.
  template <class T>
  void array(const std::vector<T>& v) {
    u64(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
};

}  // namespace shadowlab
