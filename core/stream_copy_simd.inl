// The vector copy of core/stream_copy.h, written once for AVX2 and AVX-512: included inside the
// ISA file's namespace after its stream_line (one 64-byte line: non-temporal stores, the
// destination aligned to the line). Head and tail (partial lines) by memcpy, the lines between
// by stream_line.

// Floats before dst reaches a 64-byte boundary (dst is 4-byte aligned), at most n.
[[gnu::always_inline]] inline size_t floats_to_line(const float* dst, size_t n) {
  const size_t bytes = (64 - (reinterpret_cast<uintptr_t>(dst) & 63)) & 63;
  return bytes / 4 < n ? bytes / 4 : n;
}

void copy(const float* src, size_t n, float* dst) {
  const size_t head = floats_to_line(dst, n);
  std::memcpy(dst, src, head * sizeof(float));
  size_t i = head;
  for (; i + 16 <= n; i += 16) stream_line(dst + i, src + i);
  std::memcpy(dst + i, src + i, (n - i) * sizeof(float));
}
