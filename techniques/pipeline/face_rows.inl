// The rows of techniques/pipeline/face_rows.h as plain loops, which the compiler vectorizes for the
// instruction set of the file that includes this (face_rows.cpp: baseline; face_rows_avx2.cpp,
// face_rows_avx512.cpp), inside that file's own namespace. u of texel x is u0 + (x + 0.5)·du.

void radial_row(float* row, int x0, int x1, float u0, float du, float v, float inv_far) {
  for (int x = x0; x < x1; ++x) {
    const float u = u0 + (float(x) + 0.5f) * du;
    row[x] = std::sqrt(1.0f + u * u + v * v) * inv_far / row[x];
  }
}

void paraboloid_row(float* row, int x0, int x1, float inv_far) {
  for (int x = x0; x < x1; ++x) row[x] = inv_far / row[x];
}
