#pragma once
// The instruction sets of the SIMD kernels, and the one place that chooses among them
// (docs/simd.md).
//
// Every kernel family has a scalar table, its oracle, and tables for AVX2 and AVX-512 that give
// the scalar table's bits (-ffp-contract=off, the same operations in the same order). The
// process runs the table of process_isa(): the widest set this CPU runs, narrowed by the
// environment — SHADOWLAB_ISA=scalar|avx2|avx512 gives at most that set (so that every table is
// measured and tested on one machine), SHADOWLAB_SCALAR=1 gives scalar. The mains check those
// variables strictly before any work, and refuse a set wider than the CPU's
// (lab/environment.cpp); here an unset, empty or other value leaves the CPU's choice.
#include <vector>

namespace shadowlab {

// Ordered: a CPU that runs one runs every smaller one.
enum class Isa { scalar = 0, avx2 = 1, avx512 = 2 };

// "scalar", "avx2", "avx512".
const char* isa_name(Isa isa);

// The widest set this CPU runs: avx512 needs AVX-512 F, VL and DQ (and AVX2); avx2 needs AVX2
// and FMA. The emulated build (core/simd_emulation.h) runs every kernel through SIMDe, so there
// every CPU runs avx512.
Isa cpu_isa();

// Every set this CPU runs, scalar first: what the tests compare against the scalar table.
std::vector<Isa> cpu_isas();

// The set this process's kernels use: cpu_isa() narrowed by SHADOWLAB_SCALAR and
// SHADOWLAB_ISA, read once, at the first call.
Isa process_isa();

// Kernel families whose fastest table is not the widest one on every CPU kind, by measurement
// (docs/simd.md, "Per-family choice"): the MSM lookup's 8-lane reconstruction batch, whose AVX2
// table is 8-10 % faster than its AVX-512 one on Intel Xeon (Sapphire Rapids class).
enum class IsaFamily { msm_batch };

// The table `family` runs: process_isa(), narrowed to the family's measured best on this CPU's
// vendor only when neither SHADOWLAB_ISA nor SHADOWLAB_SCALAR is set and no ScopedIsa lives,
// so that SHADOWLAB_ISA=avx512 still runs (and times) every family's widest table.
Isa family_isa(IsaFamily family);

// For tests: process_isa() returns `isa` while this lives (the previous choice after), so that
// one test binary runs the callers of every table. Not for concurrent use with other overrides.
class ScopedIsa {
 public:
  explicit ScopedIsa(Isa isa);
  ~ScopedIsa();
  ScopedIsa(const ScopedIsa&) = delete;
  ScopedIsa& operator=(const ScopedIsa&) = delete;

 private:
  int previous_;
};

}  // namespace shadowlab
