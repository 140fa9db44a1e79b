#pragma once
// Running worst errors that keep NaN. `worst = std::max(worst, e)` returns `worst` when e is
// NaN (NaN compares false), so a test tracking its largest error that way passes a NaN result:
// a barycentric of 0/0 passed every barycentric test so. worst_of keeps the first NaN.
#include <type_traits>

namespace shadowlab::test {

template <class T, class U>
T worst_of(T worst, U e) {
  const T v = T(e);
  if constexpr (std::is_floating_point_v<T>)
    if (worst != worst) return worst;
  return v <= worst ? worst : v;
}

}  // namespace shadowlab::test
