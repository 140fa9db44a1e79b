#pragma once
// core/exp_log.h's vector exp and log for AVX2 kernel files (*_avx2.cpp, compiled with -mavx2
// -mfma; docs/simd.md): exp_d4, log_d4, exp_f8, exp_wide8, log_wide8, log_split_f8 and their
// helpers in namespace shadowlab::exp_log_avx2, plain functions forced inline (no target
// attribute: the file's flags are the set).
#if !defined(__AVX2__) && !defined(SHADOWLAB_EMULATE_SIMD)
#error "core/exp_log_avx2.h is for files compiled with -mavx2 (*_avx2.cpp, *_avx512.cpp)"
#endif
#include <immintrin.h>

#include <cstdint>
#include <initializer_list>

#include "core/exp_log.h"

namespace shadowlab::exp_log_avx2 {

#define SL_EXP_LOG_AVX2 [[gnu::always_inline]] inline
#include "core/exp_log_avx2.inl"
#undef SL_EXP_LOG_AVX2

}  // namespace shadowlab::exp_log_avx2
