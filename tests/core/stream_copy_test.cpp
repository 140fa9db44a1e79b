#include "core/stream_copy.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/isa.h"

namespace shadowlab {
namespace {

// Every length 0..80 at every float offset of a 64-byte line: the destination holds the source
// exactly, and the floats just before and after it keep their guard values (a copy that
// writes a whole last line, or stops one line short, fails here).
void expect_exact_copy(StreamCopy copy) {
  std::vector<float> src(128), dst(160);
  for (size_t i = 0; i < src.size(); ++i) src[i] = float(i) + 0.25f;
  // A 64-byte-aligned base inside dst, so that `offset` is the destination's place in a line.
  const uintptr_t addr = reinterpret_cast<uintptr_t>(dst.data());
  const size_t base = ((64 - (addr & 63)) & 63) / 4 + 16;
  for (size_t offset = 0; offset < 16; ++offset)
    for (size_t n = 0; n <= 80; ++n) {
      std::fill(dst.begin(), dst.end(), -1.0f);
      float* const at = dst.data() + base + offset;
      copy(src.data() + 3, n, at);
      stream_fence();
      for (size_t i = 0; i < n; ++i)
        ASSERT_EQ(at[i], src[3 + i]) << "offset " << offset << " n " << n << " i " << i;
      ASSERT_EQ(at[-1], -1.0f) << "offset " << offset << " n " << n;
      ASSERT_EQ(at[n], -1.0f) << "offset " << offset << " n " << n;
    }
}

TEST(StreamCopy, EveryTableCopiesExactly) {
  for (const Isa isa : cpu_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(stream_copy_kernels(isa).isa, isa);
    expect_exact_copy(stream_copy_kernels(isa).copy);
  }
}

TEST(StreamCopy, TheProcessCopyIsTheProcessTable) {
  for (const Isa isa : cpu_isas()) {
    ScopedIsa scoped(isa);
    EXPECT_EQ(stream_copy_kernel(), stream_copy_kernels(isa).copy) << isa_name(isa);
  }
}

}  // namespace
}  // namespace shadowlab
