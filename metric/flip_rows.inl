// FLIP's filter rows (metric/flip_kernels.h), written once as plain loops the compiler
// vectorizes for each including file's instruction set: included inside the namespace of
// metric/flip_kernels.cpp (baseline), flip_avx2.cpp and flip_avx512.cpp. Only raw pointers,
// memcpy and GCC's vector extension: no function here is shared with code of another set.

// dst[x] += k·src[x] for x < n (a kernel's second term onto its first): element-wise IEEE
// multiply and add (no FMA under -ffp-contract=off), the same bits in every file's set.
void axpy(double k, const double* src, int n, double* dst) {
  for (int x = 0; x < n; ++x) dst[x] += k * src[x];
}

// out[x] = Σ_j k[j]·rows[j][x] for x < n, each sum from 0 in j order, 16 columns at a time in
// registers: one load per tap and one store per column.
void weighted_rows(const double* const* rows, const double* k, int taps, int n, double* out) {
  // GCC's vector extension, so that the vectorization runs across the 16 columns (left to
  // itself the compiler vectorized across the taps, with gathers: about 2× slower).
  typedef double v4d __attribute__((vector_size(32)));
  int x = 0;
  for (; x + 16 <= n; x += 16) {
    v4d acc[4] = {};
    for (int j = 0; j < taps; ++j) {
      const v4d kj = {k[j], k[j], k[j], k[j]};
      for (int q = 0; q < 4; ++q) {
        v4d v;
        std::memcpy(&v, rows[j] + x + 4 * q, sizeof v);
        acc[q] += kj * v;
      }
    }
    std::memcpy(out + x, acc, sizeof acc);
  }
  for (; x < n; ++x) {
    double a = 0.0;
    for (int j = 0; j < taps; ++j) a += k[j] * rows[j][x];
    out[x] = a;
  }
}
