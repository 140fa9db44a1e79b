// core/isa.h: the CPU's instruction sets, read here independently of __builtin_cpu_supports
// (the kernel's flags in /proc/cpuinfo), and the process's choice among them.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/isa.h"

namespace shadowlab {
namespace {

// The widest set by the CPU's flags as Linux lists them; false when there is no flags line.
bool isa_from_cpuinfo(Isa& isa) {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::set<std::string> flags;
    std::istringstream words(line.substr(line.find(':') + 1));
    for (std::string w; words >> w;) flags.insert(w);
    auto has = [&](const char* f) { return flags.count(f) != 0; };
    isa = !has("avx2") || !has("fma") ? Isa::scalar
          : has("avx512f") && has("avx512vl") && has("avx512dq") ? Isa::avx512
                                                                  : Isa::avx2;
    return true;
  }
  return false;
}

// The documented rule (core/isa.h) applied to the environment this test runs in.
Isa expected_process_isa(Isa cpu) {
  const char* scalar = std::getenv("SHADOWLAB_SCALAR");
  if (scalar && std::strcmp(scalar, "1") == 0) return Isa::scalar;
  const char* named = std::getenv("SHADOWLAB_ISA");
  if (named && std::strcmp(named, "scalar") == 0) return Isa::scalar;
  if (named && std::strcmp(named, "avx2") == 0 && cpu == Isa::avx512) return Isa::avx2;
  return cpu;
}

TEST(Isa, TheCpuIsaIsTheWidestTheCpuFlagsName) {
#if defined(SHADOWLAB_EMULATE_SIMD)
  EXPECT_EQ(cpu_isa(), Isa::avx512) << "the emulated build runs every kernel";
#else
  Isa want = Isa::scalar;
  if (!isa_from_cpuinfo(want)) GTEST_SKIP() << "no flags line in /proc/cpuinfo";
  EXPECT_EQ(cpu_isa(), want) << "cpuinfo says " << isa_name(want);
#endif
  std::printf("cpu_isa: %s\n", isa_name(cpu_isa()));
}

TEST(Isa, CpuIsasRunFromScalarToTheWidest) {
  const std::vector<Isa> isas = cpu_isas();
  ASSERT_EQ(isas.size(), size_t(int(cpu_isa()) + 1));
  for (size_t i = 0; i < isas.size(); ++i) EXPECT_EQ(int(isas[i]), int(i));
}

TEST(Isa, TheProcessIsaFollowsTheEnvironment) {
  EXPECT_EQ(process_isa(), expected_process_isa(cpu_isa()));
}

// The CPU's vendor as /proc/cpuinfo names it ("GenuineIntel", "AuthenticAMD"); empty if none.
std::string cpuinfo_vendor() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("vendor_id", 0) == 0) {
      std::istringstream words(line.substr(line.find(':') + 1));
      std::string v;
      words >> v;
      return v;
    }
  return "";
}

// The per-family rule (core/isa.h): the environment's set when it names one; otherwise MSM's
// batch at most AVX2 on Intel, the process's set elsewhere; a ScopedIsa's set while one lives.
TEST(Isa, FamiliesRunTheirMeasuredBestUnlessASetIsNamed) {
  const char* scalar = std::getenv("SHADOWLAB_SCALAR");
  const char* named = std::getenv("SHADOWLAB_ISA");
  const bool env = (scalar && std::strcmp(scalar, "1") == 0) ||
                   (named && (std::strcmp(named, "scalar") == 0 || std::strcmp(named, "avx2") == 0 ||
                              std::strcmp(named, "avx512") == 0));
  Isa want = process_isa();
#if !defined(SHADOWLAB_EMULATE_SIMD)
  if (!env && cpuinfo_vendor() == "GenuineIntel" && want == Isa::avx512) want = Isa::avx2;
#endif
  EXPECT_EQ(family_isa(IsaFamily::msm_batch), want) << cpuinfo_vendor();
  for (const Isa isa : cpu_isas()) {
    const ScopedIsa forced(isa);
    EXPECT_EQ(family_isa(IsaFamily::msm_batch), isa);
  }
  std::printf("vendor %s, msm_batch: %s\n", cpuinfo_vendor().c_str(), isa_name(family_isa(IsaFamily::msm_batch)));
}

TEST(Isa, ScopedIsaOverridesAndRestores) {
  const Isa before = process_isa();
  {
    const ScopedIsa outer(Isa::scalar);
    EXPECT_EQ(process_isa(), Isa::scalar);
    {
      const ScopedIsa inner(Isa::avx2);
      EXPECT_EQ(process_isa(), Isa::avx2);
    }
    EXPECT_EQ(process_isa(), Isa::scalar);
  }
  EXPECT_EQ(process_isa(), before);
}

TEST(Isa, NamesAreTheEnvironmentsSpelling) {
  EXPECT_STREQ(isa_name(Isa::scalar), "scalar");
  EXPECT_STREQ(isa_name(Isa::avx2), "avx2");
  EXPECT_STREQ(isa_name(Isa::avx512), "avx512");
}

}  // namespace
}  // namespace shadowlab
