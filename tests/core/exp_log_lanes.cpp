#include "exp_log_lanes.h"

namespace shadowlab::test {

#if defined(__x86_64__)
namespace exp_log_lanes_avx2 {
extern const ExpLogLanes kTable;
}
namespace exp_log_lanes_avx512 {
extern const ExpLogLanes kTable;
}
#endif

const ExpLogLanes* exp_log_lanes(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return &exp_log_lanes_avx512::kTable;
  if (isa == Isa::avx2) return &exp_log_lanes_avx2::kTable;
#endif
  (void)isa;
  return nullptr;
}

}  // namespace shadowlab::test
