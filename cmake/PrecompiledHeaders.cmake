# Precompiled headers: the standard library, Eigen and {fmt} (and GoogleTest for the tests)
# are parsed once per kind of target instead of in every file. Measured on single files
# (BENCHMARKS.md, "Continuous integration"): a test file compiles in 2-4 s less (10-16 s
# before), a core file in 0.3-1.5 s less. The fuzz preset turns them off
# (CMAKE_DISABLE_PRECOMPILE_HEADERS): its build of core is the check that every core file
# includes what it uses, which a precompiled header would hide.

# For palpa_core: its own (the library is position-independent, the tests are not).
set(PALPA_CORE_PCH <algorithm> <array> <cmath> <cstdint> <memory> <optional> <stdexcept> <string> <vector>
    <Eigen/Dense> <Eigen/Geometry> <fmt/format.h>)
# For the GoogleTest executables: core_tests builds it, the others reuse it.
set(PALPA_TEST_PCH ${PALPA_CORE_PCH} <chrono> <filesystem> <fstream> <functional> <limits> <random> <span>
    <gtest/gtest.h>)

# A GoogleTest executable that links palpa_core. Qt's tests are left out: Qt adds -fPIC,
# and a precompiled header is only used with the flags it was built with.
function(palpa_test_pch target)
  if(target STREQUAL "core_tests")
    target_precompile_headers(core_tests PRIVATE ${PALPA_TEST_PCH})
  else()
    target_precompile_headers(${target} REUSE_FROM core_tests)
  endif()
endfunction()
