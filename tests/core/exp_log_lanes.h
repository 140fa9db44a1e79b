#pragma once
// core/exp_log.h's vector forms, 16 values per call, per instruction set: the AVX2 table
// (tests/core/exp_log_lanes_avx2.cpp: core/exp_log_avx2.h's functions) and the AVX-512 one
// (exp_log_lanes_avx512.cpp: core/exp_log_avx512.h's), compiled with the ISA files' flags
// like the kernels that call them, for tests/core/exp_log_test.cpp to compare with the scalar
// functions lane by lane.
#include <cstdint>

#include "core/isa.h"

namespace shadowlab::test {

struct ExpLogLanes {
  Isa isa;
  // y[k] = f(x[k]) for k < 16, through the set's vector form of f.
  void (*exp_d)(const double* x, double* y);
  void (*log_d)(const double* x, double* y);
  void (*exp_f)(const float* x, float* y);
  void (*exp_wide)(const float* x, double* y);
  void (*log_wide)(const double* x, double* y);
  void (*log_split_f)(const float* x, float* m, int32_t* e);
  // y[i] = f(x[i]) for i < n, the scalar functions in loops the compiler vectorizes for the set.
  void (*exp_loop)(const double* x, double* y, int n);
  void (*expf_loop)(const float* x, float* y, int n);
  void (*log_loop)(const double* x, double* y, int n);
};

// The table of `isa`; nullptr for scalar (the scalar functions are the oracle).
const ExpLogLanes* exp_log_lanes(Isa isa);

}  // namespace shadowlab::test
