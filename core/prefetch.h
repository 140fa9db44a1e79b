#pragma once
// Prefetch hints for a span of memory the next loop will read and the hardware prefetcher has
// not seen coming (a row of an image far from the last one read). A hint changes no value.
#include <cstddef>

namespace shadowlab {

// One read hint per 64-byte line of the n bytes at p (and the last byte's line).
inline void prefetch_bytes(const void* p, size_t n) {
  const char* const c = static_cast<const char*>(p);
  for (size_t o = 0; o < n; o += 64) __builtin_prefetch(c + o, 0, 3);
  if (n > 0) __builtin_prefetch(c + n - 1, 0, 3);
}

}  // namespace shadowlab
