# Test targets of instructor authoring (core/author; included by tests/CMakeLists.txt).
add_executable(author_tests
  core/author/author_presets_test.cpp
  core/author/author_stiffness_map_test.cpp
  core/author/author_draft_test.cpp
  core/author/author_palpability_test.cpp
  core/author/author_problem_text_test.cpp
)
target_link_libraries(author_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(author_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(author_tests)
palpa_test_pch(author_tests)
gtest_discover_tests(author_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)
