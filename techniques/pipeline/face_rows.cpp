#include "techniques/pipeline/face_rows.h"

#include <cmath>
#include <limits>

namespace shadowlab {

#if defined(__x86_64__)
// The vector rows (face_rows_avx2.cpp, face_rows_avx512.cpp).
namespace face_rows_avx2 {
void radial_row(float* row, int x0, int x1, float u0, float du, float v, float inv_far);
void paraboloid_row(float* row, int x0, int x1, float inv_far);
float radial_tile_min(float* out, size_t stride, int x0, int x1, int y0, int y1, float u0,
                      float du, float top, float dv, float inv_far);
float paraboloid_row_min(float* row, int x0, int x1, float inv_far);
}  // namespace face_rows_avx2
namespace face_rows_avx512 {
void radial_row(float* row, int x0, int x1, float u0, float du, float v, float inv_far);
}  // namespace face_rows_avx512
#endif

namespace face_rows_scalar {

#include "techniques/pipeline/face_rows.inl"

// The plain loops of the minimum do not vectorize without -ffast-math; the vector tables have
// their own.
float radial_tile_min(float* out, size_t stride, int x0, int x1, int y0, int y1, float u0,
                      float du, float top, float dv, float inv_far) {
  float m = std::numeric_limits<float>::infinity();
  for (int y = y0; y < y1; ++y) {
    float* const row = out + size_t(y) * stride;
    radial_row(row, x0, x1, u0, du, top - (float(y) + 0.5f) * dv, inv_far);
    const float rm = face_row_min_scalar(row, x0, x1);
    m = rm < m ? rm : m;
  }
  return m;
}

float paraboloid_row_min(float* row, int x0, int x1, float inv_far) {
  paraboloid_row(row, x0, x1, inv_far);
  return face_row_min_scalar(row, x0, x1);
}

}  // namespace face_rows_scalar

namespace {

constexpr FaceRowKernels kFaceRowsScalar{Isa::scalar, face_rows_scalar::radial_row,
                                 face_rows_scalar::paraboloid_row,
                                 face_rows_scalar::radial_tile_min,
                                 face_rows_scalar::paraboloid_row_min};
#if defined(__x86_64__)
constexpr FaceRowKernels kFaceRowsAvx2{Isa::avx2, face_rows_avx2::radial_row,
                               face_rows_avx2::paraboloid_row, face_rows_avx2::radial_tile_min,
                               face_rows_avx2::paraboloid_row_min};
// The paraboloid row and the rows with their minimum are AVX2's: the 16-lane divide of the
// paraboloid row rendered dsm's faces ~10 % slower than 8 lanes on an AVX-512 Xeon.
constexpr FaceRowKernels kFaceRowsAvx512{Isa::avx512, face_rows_avx512::radial_row,
                                 face_rows_avx2::paraboloid_row,
                                 face_rows_avx2::radial_tile_min,
                                 face_rows_avx2::paraboloid_row_min};
#endif

}  // namespace

float face_row_min_scalar(const float* row, int x0, int x1) {
  float m = std::numeric_limits<float>::infinity();
  for (int x = x0; x < x1; ++x) m = row[x] < m ? row[x] : m;
  return m;
}

const FaceRowKernels& face_row_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kFaceRowsAvx512;
  if (isa == Isa::avx2) return kFaceRowsAvx2;
#endif
  (void)isa;
  return kFaceRowsScalar;
}

}  // namespace shadowlab
