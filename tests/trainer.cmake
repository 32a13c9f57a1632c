# Test targets of the live trainee exercise (core/trainer; included by tests/CMakeLists.txt).
add_executable(trainer_tests core/trainer_test.cpp core/press_control_test.cpp)
target_link_libraries(trainer_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(trainer_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(trainer_tests)
gtest_discover_tests(trainer_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)
