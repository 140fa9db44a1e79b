# SHADOWLAB_PCH: the headers most files include, precompiled once per target. The standard and
# glm headers go to every target; fmt and nlohmann/json to the targets that link them;
# GoogleTest to the test binaries. Every program of programs/ has the same flags, so they share
# one precompiled header (REUSE_FROM the first). Files with their own instruction-set flags
# (*_avx2.cpp, *_avx512.cpp; cmake/isa_sources.cmake) skip it: a header precompiled for the
# baseline cannot be loaded with other target flags.
set(SHADOWLAB_PCH_STD <algorithm> <array> <cmath> <cstdint> <cstdio> <cstring> <filesystem>
    <fstream> <limits> <map> <memory> <random> <set> <sstream> <string> <vector>)
set(SHADOWLAB_PCH_GLM <glm/glm.hpp> <glm/gtc/matrix_transform.hpp>)

function(shadowlab_pch_target target)
  get_target_property(type ${target} TYPE)
  if(NOT type MATCHES "STATIC_LIBRARY|EXECUTABLE")
    return()
  endif()
  get_target_property(srcs ${target} SOURCES)
  foreach(src IN LISTS srcs)
    if(src MATCHES "_avx(2|512)\\.cpp$")
      set_source_files_properties(${src} TARGET_DIRECTORY ${target} PROPERTIES
        SKIP_PRECOMPILE_HEADERS ON)
    endif()
  endforeach()
  get_target_property(libs ${target} LINK_LIBRARIES)
  set(headers ${SHADOWLAB_PCH_STD} ${SHADOWLAB_PCH_GLM} <fmt/format.h>)
  if(target MATCHES "^test_")
    list(APPEND headers <gtest/gtest.h> <nlohmann/json.hpp>)
  elseif(NOT target STREQUAL "shadowlab_core" AND NOT target STREQUAL "shadowlab_util"
         AND NOT target STREQUAL "shadowlab_raster" AND NOT target STREQUAL "shadowlab_metric"
         AND NOT target STREQUAL "shadowlab_raytrace")
    list(APPEND headers <nlohmann/json.hpp>)
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

# Every library, program and test binary under dir.
function(shadowlab_precompile_headers dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(programs GLOBAL PROPERTY SHADOWLAB_PROGRAMS)
  list(GET programs 0 first_program)
  foreach(t IN LISTS targets)
    if(t IN_LIST programs AND NOT t STREQUAL first_program)
      target_precompile_headers(${t} REUSE_FROM ${first_program})
    else()
      shadowlab_pch_target(${t})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    shadowlab_precompile_headers(${sub})
  endforeach()
endfunction()
