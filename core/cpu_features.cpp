#include "core/cpu_features.h"

#include <cstdlib>
#include <cstring>

namespace shadowlab {

// The emulated build (core/simd_target.h) runs every kernel through SIMDe's portable code, so
// any CPU "has" the extensions there.
bool cpu_has_avx2() {
#if defined(SHADOWLAB_EMULATE_SIMD)
  return true;
#elif defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

bool use_avx2_paths() {
  const char* force = std::getenv("SHADOWLAB_SCALAR");
  if (force && std::strcmp(force, "1") == 0) return false;
  return cpu_has_avx2();
}

bool cpu_has_avx512() {
#if defined(SHADOWLAB_EMULATE_SIMD)
  return true;
#elif defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512dq");
#else
  return false;
#endif
}

bool use_avx512_paths() {
  const char* isa = std::getenv("SHADOWLAB_ISA");
  if (isa && std::strcmp(isa, "avx2") == 0) return false;
  return use_avx2_paths() && cpu_has_avx512();
}

}  // namespace shadowlab
