// AVX2 helpers of the rotated-disk tap loops (rotated Poisson PCF and PCSS:
// techniques/lookup/lookup_batches.h): 8 lanes, each with its own face, radius and rotation. Each
// helper performs the scalar lookup's float operations in its order (techniques/lookup/map_receiver.h,
// techniques/lookup/poisson_disk.h), so the batches keep the scalar code's bits. Included inside the
// own namespace of a file compiled for AVX2 (docs/simd.md), after techniques/map_lookup_simd.h.

// The per-face table entry of each lane's face (table: MapLookupConsts' width, height, offset).
[[gnu::always_inline]] inline __m256i face_lanes(const int32_t* table, __m256i face) {
  return _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table)),
                                     face);
}

// The tap at st + radius·R(θ)·q (R: rotation by (cos θ, sin θ) = (c, s)): the scalar
// vec2(st.x + radius·(c·q.x − s·q.y), st.y + radius·(s·q.x + c·q.y)).
[[gnu::always_inline]] inline void rotated_tap(__m256 sx, __m256 sy, __m256 radius, __m256 c,
                                               __m256 s, float qx_, float qy_, __m256& tx,
                                               __m256& ty) {
  const __m256 qx = _mm256_set1_ps(qx_), qy = _mm256_set1_ps(qy_);
  tx = _mm256_add_ps(sx, _mm256_mul_ps(radius, _mm256_sub_ps(_mm256_mul_ps(c, qx),
                                                             _mm256_mul_ps(s, qy))));
  ty = _mm256_add_ps(sy, _mm256_mul_ps(radius, _mm256_add_ps(_mm256_mul_ps(s, qx),
                                                             _mm256_mul_ps(c, qy))));
}

// The stored distance of texel (x, y) of each lane's face (offset, width: face_lanes), read for
// the lanes of `mask` (0 elsewhere).
[[gnu::always_inline]] inline __m256 stored_distance(const MapLookupConsts& c, __m256i offset,
                                                     __m256i width, __m256i x, __m256i y,
                                                     __m256 mask) {
  const __m256i idx = _mm256_add_epi32(offset, _mm256_add_epi32(_mm256_mullo_epi32(y, width), x));
  return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), c.depth_base, idx, mask, 4);
}

// floor_int (map_receiver.h): truncate, step down where the truncation is above g.
[[gnu::always_inline]] inline __m256i floor_lanes(__m256 g) {
  const __m256i i = _mm256_cvttps_epi32(g);
  const __m256 above = _mm256_cmp_ps(_mm256_cvtepi32_ps(i), g, _CMP_GT_OQ);
  return _mm256_add_epi32(i, _mm256_castps_si256(above));
}
