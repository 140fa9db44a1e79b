#pragma once
// The AVX2 lookup kernels (techniques/lookup/map_lookup_simd.h), defined in map_lookup_receivers_avx2.cpp
// and map_lookup_taps_avx2.cpp (compiled for AVX2: docs/simd.md); map_lookup_simd.cpp puts them
// in the AVX2 table.
#include <cstdint>

#include "techniques/lookup/map_lookup_simd.h"

namespace shadowlab::lookup_avx2 {

void receivers8(const MapLookupConsts& c, const float* pos, const float* nrm,
                const uint8_t* covered, Receivers8& out);
void footprint_tiles8(const MapLookupConsts& c, const float* pos, const float* nrm,
                      const uint8_t* covered, int tile_shift, FootprintTiles8& out);
void depth1(const MapLookupConsts& c, const float* pos, const float* nrm, const uint8_t* covered,
            float* mask, uint32_t* texels);
void pcf(const MapLookupConsts& c, int pcf, const float* pos, const float* nrm,
         const uint8_t* covered, float* mask, uint32_t* texels, Receivers8& rest);
Faces8 faces8(const MapLookupConsts& c, int cross_pcf, const float* pos, const float* nrm,
              const uint8_t* covered, Receivers8& rest);
void merge8(const Receivers8& r, const float* vis, float* mask, uint32_t* texels);
void bilinear8_pairs(const MapLookupConsts& c, const Receivers8& r, const PlaneGather* planes,
                     int n, float (*values)[4][8], float* fx, float* fy);
void bilinear8_interleaved2(const MapLookupConsts& c, const Receivers8& r,
                            const PlaneGather& plane, float (*values)[4][8], float* fx, float* fy);
void bilinear8_interleaved4(const MapLookupConsts& c, const Receivers8& r,
                            const PlaneGather& plane, float (*values)[4][8], float* fx, float* fy);
void bilinear8_mix4(const MapLookupConsts& c, const Receivers8& r, const PlaneGather& plane,
                    double (*m)[8]);
void prefetch8(const MapLookupConsts& c, const Receivers8& r, const PlaneGather& plane,
               int floats_per_texel);

}  // namespace shadowlab::lookup_avx2
