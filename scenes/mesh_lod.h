#pragma once
// Level-of-detail meshes (the slide-projector experiment: the Stanford bunny at 5,000, 1,000 and
// 300 triangles), made with meshoptimizer's simplifier, and a small disk cache for them.
//
// simplify_mesh steps
// 1. Weld by position (exact bit equality): an OBJ may split vertices per corner (normals, uvs),
//    which the simplifier would see as borders. Normals are ignored; uvs survive only when
//    every vertex has one and no two welded vertices disagree (else the result has none).
// 2. meshopt_simplify to 3·target indices with target error 1.0 (relative to the mesh extent,
//    i.e. unconstrained: the triangle count decides, not the error).
// 3. When topology constraints (e.g. edges shared by 3+ triangles) stop it more than 5 % above
//    the target, meshopt_simplifySloppy (grid clustering, ignores topology) takes the rest of
//    the way from that result. It searches for a grid giving at most the target, so it can
//    land well below it (a fallback, not the normal path: the bunny never takes it).
// 4. Triangles left with collinear corners (zero area, seen along straight borders) are
//    dropped, then unused vertices (meshopt_optimizeVertexFetch order), and the normals are
//    recomputed for the level (area-weighted, compute_vertex_normals).
// The result keeps the input's name and material. Deterministic: same input, same bits.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/scene.h"

namespace shadowlab {

// Bump whenever simplify_mesh's output or the cache file layout changes: old cache files then
// stop matching (their key changes) instead of being trusted.
constexpr uint32_t kMeshLodVersion = 1;

// `mesh` reduced to about target_triangles triangles (see the steps above); the acceptance
// bound of the experiment is ±5 % of the target. target_triangles ≥ the mesh's count returns
// an unchanged copy (normals included). Throws InputError(where, ...) for a target of 0, an
// index count that is not a multiple of 3, an out-of-range index or a NaN/Inf position; an
// empty `where` becomes "mesh '<name>'".
Mesh simplify_mesh(const Mesh& mesh, size_t target_triangles, const std::string& where = "");

// 16 lower-case hex digits: FNV-1a 64 over kMeshLodVersion, meshoptimizer's version, the
// target and the bytes of positions, indices and uvs (what decides the result; normals, name
// and material do not).
std::string mesh_lod_key(const Mesh& mesh, size_t target_triangles);

// Path of the cache file of `key`: <cache_dir>/lod_<key>.bin.
std::string mesh_lod_cache_path(const std::string& cache_dir, const std::string& key);

// simplify_mesh through the cache file <cache_dir>/lod_<key>.bin (own binary format, native
// little-endian: magic "SLLODMS1", u32 version, u64 key, u32 vertex count, u32 index count,
// u32 has-uvs, then positions, normals, uvs (when present) as float32, indices as u32, and an
// FNV-1a 64 of every byte before it). A missing, short, long, mismatching or corrupt file is
// recomputed and overwritten (atomically: temporary file + rename); a failing write is
// reported on stderr and otherwise ignored. An empty cache_dir disables the cache (the caller
// picks the folder, e.g. raytrace's default_cache_dir()). `from_cache` (optional) says which
// happened. Name and material come from `mesh`, never from the file. Input errors are thrown
// before the cache is looked at; a target ≥ the mesh's count returns the copy uncached.
Mesh simplify_mesh_cached(const Mesh& mesh, size_t target_triangles, const std::string& cache_dir,
                          bool* from_cache = nullptr, const std::string& where = "");

}  // namespace shadowlab
