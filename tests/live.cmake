# Test targets of the live trainee exercise behind the GUI (core/live; included by
# tests/CMakeLists.txt).
add_executable(live_tests
  core/live/live_exercise_test.cpp
  core/live/press_control_test.cpp
  core/live/press_bound_test.cpp
  core/live/live_stall_test.cpp
  core/live/force_mode_load_test.cpp
  core/live/firmness_test.cpp
  core/live/stroke_trace_test.cpp
  core/live/felt_path_test.cpp
)
target_link_libraries(live_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(live_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(live_tests)
palpa_test_pch(live_tests)
gtest_discover_tests(live_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)
