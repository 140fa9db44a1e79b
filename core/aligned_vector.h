#pragma once
// std::vector storage on 64-byte (cache-line) boundaries: rows whose length is a multiple of 16
// floats then start on a line, so they can be written with whole-line non-temporal stores
// (core/stream_copy.h; a store to part of a line reads the line first, and partial
// non-temporal lines measured slower than ordinary stores: docs/performance_history.md).
// glibc's malloc gives 16-byte alignment only.
#include <cstddef>
#include <new>
#include <vector>

namespace shadowlab {

template <class T>
struct LineAlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  LineAlignedAllocator() = default;
  template <class U>
  LineAlignedAllocator(const LineAlignedAllocator<U>&) noexcept {}
  T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, size_t) noexcept { ::operator delete(p, kAlign); }
  template <class U>
  bool operator==(const LineAlignedAllocator<U>&) const noexcept { return true; }
};

// Floats on a 64-byte boundary (the depth targets' and the light maps' face storage).
using LineAlignedFloats = std::vector<float, LineAlignedAllocator<float>>;

}  // namespace shadowlab
