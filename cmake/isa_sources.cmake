# The instruction set of each SIMD kernel file (docs/simd.md): a source named *_avx2.cpp is
# compiled for AVX2 (with FMA, which -ffp-contract=off keeps from contracting anything), a
# source named *_avx512.cpp for AVX-512 F, VL, DQ and BW; every other source for the baseline.
# The flags are per file, so GCC and clang (the sanitizer and fuzz builds) compile and run the
# same vector code. Those files are kept out of the unity batches, whose other files must stay
# baseline code. The emulated build (SHADOWLAB_EMULATE_SIMD) compiles them without the flags:
# there SIMDe's portable code stands for the intrinsics.
set(SHADOWLAB_AVX2_FLAGS -mavx2 -mfma)
set(SHADOWLAB_AVX512_FLAGS -mavx512f -mavx512vl -mavx512dq -mavx512bw -mavx2 -mfma)

function(shadowlab_isa_sources target)
  get_target_property(srcs ${target} SOURCES)
  foreach(src IN LISTS srcs)
    set(flags "")
    if(src MATCHES "_avx2\\.cpp$")
      set(flags ${SHADOWLAB_AVX2_FLAGS})
    elseif(src MATCHES "_avx512\\.cpp$")
      set(flags ${SHADOWLAB_AVX512_FLAGS})
    else()
      continue()
    endif()
    set_source_files_properties(${src} TARGET_DIRECTORY ${target} PROPERTIES
      SKIP_UNITY_BUILD_INCLUSION ON)
    if(NOT SHADOWLAB_EMULATE_SIMD AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64|amd64")
      set_source_files_properties(${src} TARGET_DIRECTORY ${target} PROPERTIES
        COMPILE_OPTIONS "${flags}")
    endif()
  endforeach()
endfunction()
