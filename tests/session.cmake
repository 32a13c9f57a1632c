# Test targets of the session module (included by tests/CMakeLists.txt).
find_package(SQLite3 REQUIRED)  # the tests damage session files on purpose, through SQLite
add_executable(session_tests
  core/session_roundtrip_test.cpp
  core/session_crash_test.cpp
  core/session_corrupt_test.cpp
  core/session_recorder_test.cpp
)
target_link_libraries(session_tests PRIVATE palpa_core SQLite::SQLite3 GTest::gtest GTest::gtest_main)
target_compile_definitions(session_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(session_tests)
gtest_discover_tests(session_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)

if(PALPA_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
  add_executable(session_bench bench/session_bench.cpp)
  target_link_libraries(session_bench PRIVATE palpa_core benchmark::benchmark)
  target_compile_definitions(session_bench PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  palpa_warnings(session_bench)
endif()
