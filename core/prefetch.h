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

// One prefetch per 4 KiB page of the n bytes at p (and the last byte's page), a few rows before
// non-temporal stores fill them: the stores need each page's address translation, and the first
// store to a page whose translation is out of the TLB waits for the page walk (on the 2-core VMs
// we measure on, a load that misses both the caches and the TLB takes ~250 ns), where the
// prefetch walks it ahead. (On the baseline x86-64 target, which has no PREFETCHW, GCC emits
// prefetchnta for this write hint of locality 0.) One line per page is brought in, ~1.5 % of
// what the stores write. docs/performance_history.md.
inline void prefetch_pages(void* p, size_t n) {
  char* const c = static_cast<char*>(p);
  for (size_t o = 0; o < n; o += 4096) __builtin_prefetch(c + o, 1, 0);
  if (n > 0) __builtin_prefetch(c + n - 1, 1, 0);
}

}  // namespace shadowlab
