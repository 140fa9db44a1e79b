#include "scenes/mesh_lod.h"

#include <meshoptimizer.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/cache_file.h"
#include "core/error.h"
#include "core/hash.h"

namespace shadowlab {
namespace {

// meshoptimizer reads positions as 3 packed floats with a stride; the arrays are passed as is.
static_assert(sizeof(vec3) == 3 * sizeof(float), "vec3 must be 3 packed floats");
static_assert(sizeof(vec2) == 2 * sizeof(float), "vec2 must be 2 packed floats");

constexpr char kMagic[8] = {'S', 'L', 'L', 'O', 'D', 'M', 'S', '1'};
// magic, u32 version, u64 key, u32 vertex count, u32 index count, u32 has-uvs.
constexpr size_t kHeaderBytes = sizeof(kMagic) + 4 + 8 + 3 * 4;
constexpr uint32_t kNoVertex = ~0u;  // meshoptimizer's remap value of an unused vertex

uint64_t lod_hash(const Mesh& mesh, size_t target_triangles) {
  Fnv1a h;
  h.u64(kMeshLodVersion);
  h.u64(MESHOPTIMIZER_VERSION);  // another simplifier version may give other triangles
  h.u64(target_triangles);
  h.array(mesh.positions);
  h.array(mesh.indices);
  h.array(mesh.uvs);
  return h.h;
}

std::string hex16(uint64_t v) {
  return fmt::format("{:016x}", v);
}

std::string where_or_default(const Mesh& mesh, const std::string& where) {
  return where.empty() ? "mesh '" + mesh.name + "'" : where;
}

// Throws InputError for what would make meshoptimizer read out of bounds or give garbage.
void check_input(const Mesh& mesh, size_t target_triangles, const std::string& where) {
  if (target_triangles == 0)
    throw InputError(where, "level-of-detail target must be at least 1 triangle");
  if (mesh.indices.size() % 3 != 0)
    throw InputError(where, "index count " + std::to_string(mesh.indices.size()) +
                                " is not a multiple of 3");
  for (uint32_t i : mesh.indices)
    if (i >= mesh.positions.size())
      throw InputError(where, "index " + std::to_string(i) + " is out of range (" +
                                  std::to_string(mesh.positions.size()) + " vertices)");
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    if (!is_finite(mesh.positions[v]))
      throw InputError(where, "vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
    throw InputError(where, "uv count differs from vertex count");
}

// The uvs of the welded vertices, or empty when the mesh has none or two vertices welded into
// one disagree (a uv seam): a single uv per position cannot be chosen without distortion.
std::vector<vec2> welded_uvs(const Mesh& mesh, const std::vector<uint32_t>& remap,
                             size_t welded_count) {
  if (mesh.uvs.empty()) return {};
  std::vector<vec2> uvs(welded_count);
  std::vector<char> seen(welded_count, 0);
  for (size_t v = 0; v < remap.size(); ++v) {
    const uint32_t w = remap[v];
    if (w == kNoVertex) continue;
    if (!seen[w]) {
      uvs[w] = mesh.uvs[v];
      seen[w] = 1;
    } else if (std::memcmp(&uvs[w], &mesh.uvs[v], sizeof(vec2)) != 0) {
      return {};
    }
  }
  return uvs;
}

void put_bytes(std::vector<char>& out, const void* data, size_t n) {
  // resize + memcpy, not insert: GCC 12 warns falsely (-Wstringop-overflow) on the insert.
  const size_t at = out.size();
  out.resize(at + n);
  if (n > 0) std::memcpy(out.data() + at, data, n);
}
template <class T>
void put(std::vector<char>& out, T v) {
  put_bytes(out, &v, sizeof v);
}
template <class T>
T get(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Reads the cache file into `out` (positions, normals, uvs, indices only) when it exists and
// passes every check; otherwise returns false.
bool load_lod(const std::string& path, uint64_t key, Mesh& out) {
  std::vector<char> buf;
  if (!read_file_bytes(path, kHeaderBytes + sizeof(uint64_t), buf)) return false;
  const size_t size = buf.size();

  // Header.
  if (std::memcmp(buf.data(), kMagic, sizeof kMagic) != 0) return false;
  const char* q = buf.data() + sizeof kMagic;
  if (get<uint32_t>(q) != kMeshLodVersion || get<uint64_t>(q + 4) != key) return false;
  const uint64_t nv = get<uint32_t>(q + 12), ni = get<uint32_t>(q + 16);
  const uint32_t has_uvs = get<uint32_t>(q + 20);
  if (has_uvs > 1 || ni % 3 != 0) return false;
  // u64 arithmetic: u32 counts cannot overflow it.
  const uint64_t expected = kHeaderBytes + nv * (2 * sizeof(vec3) + has_uvs * sizeof(vec2)) +
                            ni * sizeof(uint32_t) + sizeof(uint64_t);
  if (uint64_t(size) != expected) return false;

  // Checksum over everything before it.
  const size_t body = size_t(size) - sizeof(uint64_t);
  Fnv1a h;
  h.bytes(buf.data(), body);
  if (get<uint64_t>(buf.data() + body) != h.h) return false;

  Mesh m;
  m.positions.resize(nv);
  m.normals.resize(nv);
  m.uvs.resize(has_uvs ? nv : 0);
  m.indices.resize(ni);
  const char* p = buf.data() + kHeaderBytes;
  auto take = [&p](auto& v) {
    const size_t n = v.size() * sizeof(v[0]);
    if (n) std::memcpy(v.data(), p, n);
    p += n;
  };
  take(m.positions);
  take(m.normals);
  take(m.uvs);
  take(m.indices);
  for (uint32_t i : m.indices)
    if (i >= nv) return false;
  for (size_t v = 0; v < nv; ++v)
    if (!is_finite(m.positions[v]) || !is_finite(m.normals[v])) return false;
  out = std::move(m);
  return true;
}

// Writes the arrays of `lod` atomically (temporary file in the same folder + rename), creating
// the folder if needed. Throws InputError naming the path when it cannot.
void store_lod(const std::string& dir, const std::string& path, uint64_t key, const Mesh& lod) {
  SL_CHECK_EQ(lod.normals.size(), lod.positions.size());
  SL_CHECK(lod.uvs.empty() || lod.uvs.size() == lod.positions.size());
  SL_CHECK_LE(lod.indices.size(), size_t(UINT32_MAX));  // counts are stored as u32
  std::vector<char> buf;
  // The whole file at once.
  buf.reserve(kHeaderBytes + sizeof(uint64_t) +
              lod.positions.size() * 2 * sizeof(vec3) + lod.uvs.size() * sizeof(vec2) +
              lod.indices.size() * sizeof(uint32_t));
  put_bytes(buf, kMagic, sizeof kMagic);
  put<uint32_t>(buf, kMeshLodVersion);
  put<uint64_t>(buf, key);
  put<uint32_t>(buf, uint32_t(lod.positions.size()));
  put<uint32_t>(buf, uint32_t(lod.indices.size()));
  put<uint32_t>(buf, lod.uvs.empty() ? 0 : 1);
  put_bytes(buf, lod.positions.data(), lod.positions.size() * sizeof(vec3));
  put_bytes(buf, lod.normals.data(), lod.normals.size() * sizeof(vec3));
  put_bytes(buf, lod.uvs.data(), lod.uvs.size() * sizeof(vec2));
  put_bytes(buf, lod.indices.data(), lod.indices.size() * sizeof(uint32_t));
  Fnv1a h;
  h.bytes(buf.data(), buf.size());
  put<uint64_t>(buf, h.h);

  write_file_atomically(dir, path, buf, "LOD cache file");
}

}  // namespace

Mesh simplify_mesh(const Mesh& mesh, size_t target_triangles, const std::string& where) {
  check_input(mesh, target_triangles, where_or_default(mesh, where));
  if (target_triangles >= mesh.triangle_count()) return mesh;

  // 1. Weld by exact position; unused vertices drop out of the remap.
  const size_t n = mesh.positions.size();
  std::vector<uint32_t> remap(n);
  const size_t welded_count =
      meshopt_generateVertexRemap(remap.data(), mesh.indices.data(), mesh.indices.size(),
                                  mesh.positions.data(), n, sizeof(vec3));
  std::vector<vec3> positions(welded_count);
  meshopt_remapVertexBuffer(positions.data(), mesh.positions.data(), n, sizeof(vec3),
                            remap.data());
  std::vector<uint32_t> welded(mesh.indices.size());
  meshopt_remapIndexBuffer(welded.data(), mesh.indices.data(), welded.size(), remap.data());
  std::vector<vec2> uvs = welded_uvs(mesh, remap, welded_count);

  // Triangles that welding made degenerate (repeated index) cover nothing: drop them.
  std::vector<uint32_t> indices;
  indices.reserve(welded.size());
  for (size_t t = 0; t < welded.size(); t += 3) {
    const uint32_t a = welded[t], b = welded[t + 1], c = welded[t + 2];
    if (a == b || b == c || c == a) continue;
    indices.insert(indices.end(), {a, b, c});
  }

  // 2. Edge collapses towards 3·target indices; error 1.0 = the whole extent, unconstrained.
  const size_t target_indices = 3 * target_triangles;
  if (indices.size() > target_indices) {
    std::vector<uint32_t> out(indices.size());  // worst case is the input size
    out.resize(meshopt_simplify(out.data(), indices.data(), indices.size(), &positions[0].x,
                                positions.size(), sizeof(vec3), target_indices, 1.0f, 0,
                                nullptr));
    indices.swap(out);
  }

  // 3. Topology (non-manifold edges, flips) can stop the collapses early; more than 5 % above
  // the target, grid clustering takes the rest of the way (it ignores topology).
  if (20 * indices.size() > 21 * target_indices) {
    std::vector<uint32_t> out(indices.size());
    out.resize(meshopt_simplifySloppy(out.data(), indices.data(), indices.size(),
                                      &positions[0].x, positions.size(), sizeof(vec3),
                                      target_indices, 1.0f, nullptr));
    indices.swap(out);
  }

  // Collapses along a straight border can leave triangles with collinear corners: they cover
  // nothing and have no normal (their vertices would get the fallback normal), so drop them.
  size_t kept_indices = 0;
  for (size_t t = 0; t < indices.size(); t += 3) {
    const vec3 &a = positions[indices[t]], &b = positions[indices[t + 1]],
               &c = positions[indices[t + 2]];
    const vec3 n = glm::cross(b - a, c - a);
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) continue;
    for (int k = 0; k < 3; ++k) indices[kept_indices++] = indices[t + size_t(k)];
  }
  indices.resize(kept_indices);

  // 4. Keep only the vertices still used, in first-use order.
  std::vector<uint32_t> fetch(positions.size());
  const size_t kept = meshopt_optimizeVertexFetchRemap(fetch.data(), indices.data(),
                                                       indices.size(), positions.size());
  Mesh lod;
  lod.name = mesh.name;
  lod.material = mesh.material;
  lod.positions.resize(kept);
  meshopt_remapVertexBuffer(lod.positions.data(), positions.data(), positions.size(),
                            sizeof(vec3), fetch.data());
  if (!uvs.empty()) {
    lod.uvs.resize(kept);
    meshopt_remapVertexBuffer(lod.uvs.data(), uvs.data(), uvs.size(), sizeof(vec2),
                              fetch.data());
  }
  lod.indices.resize(indices.size());
  meshopt_remapIndexBuffer(lod.indices.data(), indices.data(), indices.size(), fetch.data());

  // The input's normals belong to the full surface: recompute them from the level's faces.
  lod.normals.clear();
  compute_vertex_normals(lod);
  return lod;
}

std::string mesh_lod_key(const Mesh& mesh, size_t target_triangles) {
  return hex16(lod_hash(mesh, target_triangles));
}

std::string mesh_lod_cache_path(const std::string& cache_dir, const std::string& key) {
  return (std::filesystem::path(cache_dir) / ("lod_" + key + ".bin")).string();
}

Mesh simplify_mesh_cached(const Mesh& mesh, size_t target_triangles, const std::string& cache_dir,
                          bool* from_cache, const std::string& where) {
  if (from_cache) *from_cache = false;
  check_input(mesh, target_triangles, where_or_default(mesh, where));
  if (cache_dir.empty() || target_triangles >= mesh.triangle_count())
    return simplify_mesh(mesh, target_triangles, where);

  const uint64_t key = lod_hash(mesh, target_triangles);
  const std::string path = mesh_lod_cache_path(cache_dir, hex16(key));
  Mesh lod;
  if (load_lod(path, key, lod)) {
    lod.name = mesh.name;
    lod.material = mesh.material;
    if (from_cache) *from_cache = true;
    return lod;
  }
  lod = simplify_mesh(mesh, target_triangles, where);
  try {
    store_lod(cache_dir, path, key, lod);
  } catch (const InputError& e) {
    std::fprintf(stderr, "warning: level of detail not cached: %s\n", e.what());
  }
  return lod;
}

}  // namespace shadowlab
