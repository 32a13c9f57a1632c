# Test targets of the score module (included by tests/CMakeLists.txt).
find_package(GTest REQUIRED)
include(GoogleTest)

add_executable(score_tests
  core/score/score_thresholds_test.cpp
  core/score/score_marks_test.cpp
  core/score/score_coverage_test.cpp
  core/score/score_session_test.cpp
  core/score/score_pattern_test.cpp
  core/score/nearest_distance_test.cpp
  core/score/score_stream_test.cpp
  core/score/score_from_json_test.cpp
  core/score/score_figures_test.cpp
  core/score/live_coverage_test.cpp
)
find_package(SQLite3 REQUIRED)  # score_stream_test edits copies of sessions (events, damage)
target_link_libraries(score_tests PRIVATE palpa_core SQLite::SQLite3 GTest::gtest GTest::gtest_main)
target_compile_definitions(score_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(score_tests)
palpa_test_pch(score_tests)
gtest_discover_tests(score_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)

# Scoring throughput on a synthetic 5-minute 1 kHz session.
if(PALPA_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
  add_executable(score_bench
    bench/score_bench.cpp
  )
  target_link_libraries(score_bench PRIVATE palpa_core benchmark::benchmark)
  target_compile_definitions(score_bench PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  palpa_warnings(score_bench)
endif()
