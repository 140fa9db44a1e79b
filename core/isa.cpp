#include "core/isa.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace shadowlab {
namespace {

Isa detect_cpu_isa() {
#if defined(SHADOWLAB_EMULATE_SIMD)
  return Isa::avx512;
#elif defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return Isa::scalar;
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512dq"))
    return Isa::avx512;
  return Isa::avx2;
#else
  return Isa::scalar;
#endif
}

// The process's set from the CPU and the environment, and whether the environment named one.
struct EnvironmentIsa {
  Isa isa;
  bool named;
};

EnvironmentIsa resolve_environment_isa() {
  const Isa cpu = cpu_isa();
  const char* scalar = std::getenv("SHADOWLAB_SCALAR");
  if (scalar && std::strcmp(scalar, "1") == 0) return {Isa::scalar, true};
  // SHADOWLAB_ISA names the widest set to use; never wider than the CPU's (the programs refuse
  // such a request before any work: lab/environment.cpp).
  const char* named = std::getenv("SHADOWLAB_ISA");
  if (named && std::strcmp(named, "scalar") == 0) return {Isa::scalar, true};
  if (named && std::strcmp(named, "avx2") == 0) return {cpu > Isa::avx2 ? Isa::avx2 : cpu, true};
  return {cpu, named && std::strcmp(named, "avx512") == 0};
}

const EnvironmentIsa& environment_isa() {
  static const EnvironmentIsa e = resolve_environment_isa();
  return e;
}

// ScopedIsa's override: -1 when none, else the Isa's value.
std::atomic<int> g_override{-1};

bool detect_intel() {
#if defined(SHADOWLAB_EMULATE_SIMD)
  return false;
#elif defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  return __builtin_cpu_is("intel");
#else
  return false;
#endif
}

bool cpu_is_intel() {
  static const bool intel = detect_intel();
  return intel;
}

// The widest table worth running for a family on this CPU's vendor (docs/simd.md).
Isa family_best(IsaFamily family) {
  switch (family) {
    case IsaFamily::msm_batch: return cpu_is_intel() ? Isa::avx2 : Isa::avx512;
  }
  return Isa::avx512;
}

}  // namespace

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::avx2: return "avx2";
    case Isa::avx512: return "avx512";
    default: return "scalar";
  }
}

Isa cpu_isa() {
  static const Isa isa = detect_cpu_isa();
  return isa;
}

std::vector<Isa> cpu_isas() {
  std::vector<Isa> isas;
  for (int i = 0; i <= int(cpu_isa()); ++i) isas.push_back(Isa(i));
  return isas;
}

Isa process_isa() {
  const int forced = g_override.load(std::memory_order_relaxed);
  if (forced >= 0) return Isa(forced);
  return environment_isa().isa;
}

Isa family_isa(IsaFamily family) {
  const Isa isa = process_isa();
  if (g_override.load(std::memory_order_relaxed) >= 0 || environment_isa().named) return isa;
  const Isa best = family_best(family);
  return best < isa ? best : isa;
}

ScopedIsa::ScopedIsa(Isa isa) : previous_(g_override.exchange(int(isa))) {}
ScopedIsa::~ScopedIsa() { g_override.store(previous_); }

}  // namespace shadowlab
