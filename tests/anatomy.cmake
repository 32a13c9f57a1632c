# Test targets of the anatomy import's fitter (core/anatomy; included by tests/CMakeLists.txt).
add_executable(anatomy_tests
  core/anatomy/fit_volume_test.cpp
  core/anatomy/import_volume_test.cpp
  core/anatomy/label_values_test.cpp
  core/anatomy/import_mesh_test.cpp
)
target_link_libraries(anatomy_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(anatomy_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(anatomy_tests)
palpa_test_pch(anatomy_tests)
gtest_discover_tests(anatomy_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)
