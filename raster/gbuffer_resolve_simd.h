#pragma once
// The SIMD paths of the GBuffer resolve for 8 (AVX2) or 16 (AVX-512) neighbouring pixels of one
// row: all showing the same triangle (two thirds of the 8-pixel runs on room100k at 1024×768),
// or each its own. They perform the scalar resolve's IEEE operations in the same order
// (gbuffer_pass.cpp is their oracle), so the GBuffer is bit-identical either way; a test
// compares both. The resolve writes position, geometric normal and depth; the shading normal
// and uv are deferred (core/gbuffer_shading.h).
#include <cstdint>

#include "core/isa.h"
#include "core/math.h"

namespace shadowlab {

// The per-triangle terms and camera constants the 8 pixels share.
struct ResolveRun8 {
  // Camera: d = (forward + (nx·sx)·right) + (ny·sy)·up for the pixel centre (nx, ny in NDC).
  vec3 eye, forward, right, up;
  float sx, sy;
  int width, height;
  // forward + (nx·sx)·right of every column x, component c at columns[c·width + x] (the AVX2
  // paths load it; the AVX-512 path computes it).
  const float* columns = nullptr;
  // Triangle: Möller–Trumbore terms (e1, e2 and e2·q, with s = eye − p0 and q = s × e1), unit
  // normal. The barycentric terms (s, q) are not needed: the resolve writes no interpolated
  // attribute.
  vec3 e1, e2, gn;
  float e2q;
};

// Resolves pixels x .. x+7 of row y: reads 8 values of 1/w, writes 8 entries of each output.
using ResolveRun8Fn = void (*)(const ResolveRun8& r, int x, int y, const float* inv_w,
                               vec3* position, vec3* geo_normal, float* depth);

// 8 neighbouring pixels of one row that show different triangles: each lane its own
// triangle's vertices (structure of arrays: [vertex][component][lane]), from which the kernel
// derives ResolveRun8's terms with the scalar resolve's operations, 8 triangles at a time (a
// scalar triangle load was dominated by the normal's square root and division). Lanes showing
// no triangle may hold anything finite: the caller writes their empty values.
struct ResolveLanes8 {
  alignas(32) float v[3][3][8];
};
// The camera fields of `camera` (its triangle fields unused) and the lanes' triangles.
using ResolveLanes8Fn = void (*)(const ResolveRun8& camera, const ResolveLanes8& lanes, int x,
                                 int y, const float* inv_w, vec3* position, vec3* geo_normal,
                                 float* depth);

// 16 neighbouring pixels in AVX-512, each lane its own triangle as in ResolveLanes8 (runs of
// one triangle are filled with one masked store per term).
struct ResolveLanes16 {
  alignas(64) float e1[3][16], e2[3][16], gn[3][16], e2q[16];
  alignas(64) uint32_t mesh[16], prim[16];  // the lane's mesh and triangle index in it
  uint32_t covered = 0;  // bit k: lane k shows a triangle (else its empty values)
};
// Writes all 16 pixels' layers: the covered lanes' resolve, the others' empty values (position
// and normal 0, depth +inf, ids kNoPrimitive, covered 0), as the scalar resolve does.
using ResolveLanes16Fn = void (*)(const ResolveRun8& camera, const ResolveLanes16& lanes, int x,
                                  int y, const float* inv_w, vec3* position, vec3* geo_normal,
                                  float* depth, uint32_t* mesh_id, uint32_t* prim_id,
                                  uint8_t* covered);
// The first pixels of the runs of equal ids among ids[0 .. 15] (bit k: ids[k] != ids[k − 1];
// bit 0 always set), and in *covered the pixels that show a triangle (ids[k] != kNoPrimitive).
using ResolveLanes16RunsFn = uint32_t (*)(const uint32_t* ids, uint32_t* covered);
// Lanes `mask` of `l` get one triangle's terms: one masked store of each broadcast term.
using ResolveLanes16FillFn = void (*)(ResolveLanes16& l, uint32_t mask, const vec3& e1,
                                      const vec3& e2, const vec3& gn, float e2q, uint32_t mesh,
                                      uint32_t prim);

// The family's table per instruction set (docs/simd.md). The scalar table has no kernels
// (nullptr: the resolve's own loop in gbuffer_pass.cpp, the oracle); the AVX2 table has the
// 8-pixel paths (raster/gbuffer_resolve_simd_avx2.cpp); the AVX-512 table those and the 16-pixel
// path with its two helpers (gbuffer_resolve_simd_avx512.cpp).
struct GBufferResolveKernels {
  Isa isa;  // the widest instruction set the table's kernels were compiled for
  ResolveRun8Fn run8;
  ResolveLanes8Fn lanes8;
  ResolveLanes16Fn lanes16;
  ResolveLanes16RunsFn lanes16_runs;
  ResolveLanes16FillFn lanes16_fill;
};
const GBufferResolveKernels& gbuffer_resolve_kernels(Isa isa);

}  // namespace shadowlab
