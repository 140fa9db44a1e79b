#pragma once
// On-disk cache of reference masks, keyed by a hash of everything that determines the image, so
// the Embree scene is built only when a reference is not cached yet (docs/design.md §7).
//
// File: <dir>/<key>.slref, a small own binary format (native little-endian):
//   8 bytes  magic "SLREFMK1"
//   16 bytes the key (16 hex digits, ASCII)
//   4 × u32  format version, width, height, channels
//   float32  width·height·channels values (the Image<float> data, planar)
//   u64      FNV-1a 64 of every byte before it
// A file that is short, long, has another magic/version/key, an absurd size, a bad checksum or
// a value outside [0,1] is ignored (recomputed), never trusted. Files are written to a unique
// temporary name in the same folder and renamed into place, so readers never see a partial file.
#include <cstdint>
#include <string>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/scene.h"

namespace shadowlab {

// Bump whenever the reference algorithm (sampling, offsets, alpha rule, ...) or the key's
// contents change: old cache entries then stop matching.
constexpr uint32_t kReferenceVersion = 1;

// 16 lower-case hex digits: FNV-1a 64 over kReferenceVersion, every mesh's positions, indices,
// uvs and material index, every material's alpha texture (size and alpha channel) and cutoff,
// the light's position and radius, the GBuffer size and, per pixel, covered and (where covered)
// position and geometric normal, spp and seed. Floats are hashed by their bits. Things that
// cannot change the mask (albedo, shading normals, names, camera, light near/far) are left out.
std::string reference_key(const Scene& scene, const GBuffer& gbuffer, int spp, uint64_t seed);

// Cache folder: $SHADOWLAB_CACHE if set and non-empty; else $XDG_CACHE_HOME/shadowlab if
// XDG_CACHE_HOME is an absolute path; else $HOME/.cache/shadowlab; else "" (caching disabled).
std::string default_cache_dir();

// Path of the cache file of `key` inside `dir`.
std::string cached_reference_path(const std::string& dir, const std::string& key);

// Loads <dir>/<key>.slref into `out` and returns true if it exists and passes every check;
// otherwise returns false and leaves `out` untouched. An empty dir returns false.
bool load_cached_reference(const std::string& dir, const std::string& key, ImageF& out);

// Writes the mask atomically (temporary file + rename), creating `dir` if needed. Throws
// InputError naming the path if it cannot be written. An empty dir does nothing.
void store_cached_reference(const std::string& dir, const std::string& key, const ImageF& mask);

// The reference mask, from the cache when present, else computed (soft_visibility with spp and
// seed; hard when the light radius is 0) and stored. A failing store is reported on stderr and
// otherwise ignored (the result is still returned). `from_cache` (optional) says which happened.
ImageF cached_reference_mask(const Scene& scene, const GBuffer& gbuffer, int spp, uint64_t seed,
                             const std::string& dir, bool* from_cache = nullptr);

}  // namespace shadowlab
