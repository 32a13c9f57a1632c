# Test targets of the scripted exercises (core/scripted: headless scripted trainees; included
# by tests/CMakeLists.txt).
add_executable(scripted_tests
  core/scripted/scripted_placement_test.cpp
  core/scripted/scripted_trainee_test.cpp
  core/scripted/scripted_run_test.cpp
)
target_link_libraries(scripted_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(scripted_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(scripted_tests)
palpa_test_pch(scripted_tests)
gtest_discover_tests(scripted_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)

# palpa-cli exercise end to end: styles, the session file, determinism, refusals.
add_test(NAME cli.exercise COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_exercise_cli.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR})
add_test(NAME data.sample_sessions COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_sample_sessions.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR})
