# Precompiled headers for the sanitized build's GoogleTest executables: the standard
# library, Eigen, {fmt} and GoogleTest are parsed once (core_tests builds the header, the
# others reuse it) instead of in each test file. Measured one file at a time
# (BENCHMARKS.md, "Continuous integration"): a test file compiles in 2-4 s less (10-16 s
# before). Only under the sanitizers with GCC (the dev presets): at -O3 GCC 12 reports a
# -Warray-bounds false positive inside <string> when it comes from a precompiled header,
# and the release build and clang's fuzz build keep checking that every file includes
# what it uses, which a precompiled header would hide.
set(PALPA_TEST_PCH <algorithm> <array> <chrono> <cmath> <cstdint> <filesystem> <fstream> <functional> <limits>
    <memory> <optional> <random> <span> <stdexcept> <string> <vector>
    <Eigen/Dense> <Eigen/Geometry> <fmt/format.h> <gtest/gtest.h>)

# A GoogleTest executable that links palpa_core. Qt's tests are left out: Qt adds -fPIC,
# and a precompiled header is only used with the flags it was built with.
function(palpa_test_pch target)
  if(NOT (PALPA_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU"))
    return()
  endif()
  # GCC uses a precompiled header only where the command line defines the same macros.
  target_compile_definitions(${target} PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  if(target STREQUAL "core_tests")
    target_precompile_headers(core_tests PRIVATE ${PALPA_TEST_PCH})
  else()
    target_precompile_headers(${target} REUSE_FROM core_tests)
  endif()
endfunction()
