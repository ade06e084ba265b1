# Precompiled headers for Talus's own targets (build time only; nothing is installed).
#
# Nearly every translation unit includes Eigen's dense core through talus/core/types.hpp, every
# test GoogleTest, and most of the experiments nlohmann/json: about 140,000 lines parsed again
# for every file. talus_use_pch(TARGET FLAVOUR) makes TARGET include one precompiled copy:
#   lib   the static layers (position-independent code): Eigen + standard headers
#   app   the experiments library, the CLI, the notebooks and the benchmarks: lib's + json
#   test  the GoogleTest executables: lib's + gtest
# GCC rejects a header precompiled with other code-generation flags (-fPIC, -fsanitize=...), so
# each flavour is compiled once by a host target with exactly its users' flags (talus_warnings,
# the configuration's flags), and every user reuses it (REUSE_FROM).
#
# Measured (GCC 12, loaded 2-core machine, CPU seconds, CCACHE_DISABLE=1): a clean Makefiles
# build of talus_core + test_core 68.1 -> 52.2 (Release, both precompiled headers included); the
# same 23 layer files compiled with and without 40.6 vs 70.2 (Release), 16 files 24.9 vs 46.7
# (ASan+UBSan, -O1 -g1); each flavour's header costs 5-7 s once per build.
#
# TALUS_PCH: AUTO (default) precompiles unless a compiler launcher such as ccache is set (ccache
# would miss on every precompiled compile unless configured with sloppiness=pch_defines,
# time_macros); ON or OFF force it.
set(TALUS_PCH AUTO CACHE STRING "Precompile the heavy third-party headers (AUTO, ON, OFF)")
set_property(CACHE TALUS_PCH PROPERTY STRINGS AUTO ON OFF)
if(TALUS_PCH STREQUAL "AUTO")
  if(CMAKE_CXX_COMPILER_LAUNCHER OR DEFINED ENV{CMAKE_CXX_COMPILER_LAUNCHER})
    set(TALUS_PCH_ENABLED OFF)
  else()
    set(TALUS_PCH_ENABLED ON)
  endif()
elseif(TALUS_PCH)
  set(TALUS_PCH_ENABLED ON)
else()
  set(TALUS_PCH_ENABLED OFF)
endif()
if(TALUS_PCH_ENABLED)
  message(STATUS "Precompiled headers: on (TALUS_PCH=${TALUS_PCH})")
else()
  message(STATUS "Precompiled headers: off (TALUS_PCH=${TALUS_PCH})")
endif()

# Headers every flavour precompiles: Eigen's dense core and the standard headers most files use.
set(_talus_pch_common <Eigen/Core> <Eigen/Geometry> <algorithm> <array> <cmath> <cstddef>
                      <cstdint> <functional> <limits> <memory> <optional> <stdexcept> <string>
                      <string_view> <utility> <vector>)

function(talus_use_pch target flavour)
  if(NOT TALUS_PCH_ENABLED)
    return()
  endif()
  set(host talus_pch_${flavour})
  if(NOT TARGET ${host})
    set(source ${PROJECT_BINARY_DIR}/talus_pch/${flavour}.cpp)
    file(CONFIGURE OUTPUT ${source} CONTENT "// Host of the precompiled header ${host}.\n")
    add_library(${host} OBJECT ${source})
    target_link_libraries(${host} PRIVATE Eigen3::Eigen talus_warnings)
    set(headers ${_talus_pch_common})
    if(flavour STREQUAL "lib")
      set_target_properties(${host} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    elseif(flavour STREQUAL "app")
      if(TARGET nlohmann_json::nlohmann_json)
        target_link_libraries(${host} PRIVATE nlohmann_json::nlohmann_json)
        list(APPEND headers <nlohmann/json.hpp>)
      endif()
    elseif(flavour STREQUAL "test")
      target_link_libraries(${host} PRIVATE GTest::gtest)
      list(APPEND headers <gtest/gtest.h>)
    else()
      message(FATAL_ERROR "talus_use_pch: unknown flavour '${flavour}'")
    endif()
    target_precompile_headers(${host} PRIVATE ${headers})
  endif()
  target_precompile_headers(${target} REUSE_FROM ${host})
endfunction()
