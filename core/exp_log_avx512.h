#pragma once
// core/exp_log.h's vector exp and log for AVX-512 kernel files (*_avx512.cpp, compiled with
// -mavx512f -mavx512vl -mavx512dq -mavx512bw; docs/simd.md): exp_d8, log_d8, exp_f16,
// exp_wide16, log_wide16, log_split_f16, and the AVX2 forms of core/exp_log_avx2.h, all in
// namespace shadowlab::exp_log_avx512 (so that no function compiled for AVX-512 shares a name
// with one compiled for AVX2), plain functions forced inline.
#if !defined(__AVX512F__) && !defined(SHADOWLAB_EMULATE_SIMD)
#error "core/exp_log_avx512.h is for files compiled with -mavx512f (*_avx512.cpp)"
#endif
#include <immintrin.h>

#include <cstdint>
#include <initializer_list>

#include "core/exp_log.h"

namespace shadowlab::exp_log_avx512 {

#define SL_EXP_LOG_AVX2 [[gnu::always_inline]] inline
#define SL_EXP_LOG_AVX512 [[gnu::always_inline]] inline
#include "core/exp_log_avx2.inl"
#include "core/exp_log_avx512.inl"
#undef SL_EXP_LOG_AVX2
#undef SL_EXP_LOG_AVX512

}  // namespace shadowlab::exp_log_avx512
