// The AVX-512 rows of techniques/pipeline/face_rows.h: face_rows.inl's loops vectorized for AVX-512.
// Compiled with -mavx512f -mavx512vl -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <cmath>

#include "techniques/pipeline/face_rows.h"

namespace shadowlab::face_rows_avx512 {

#include "techniques/pipeline/face_rows.inl"

}  // namespace shadowlab::face_rows_avx512
#endif
