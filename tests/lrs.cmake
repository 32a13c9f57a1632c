# Test targets of the LRS client (included by tests/CMakeLists.txt).
add_executable(lrs_tests lrs/outbox_test.cpp)
target_link_libraries(lrs_tests PRIVATE palpa_lrs GTest::gtest GTest::gtest_main)
palpa_warnings(lrs_tests)
gtest_discover_tests(lrs_tests TEST_PREFIX "lrs." DISCOVERY_TIMEOUT 60)

# Statements checked with Learning Locker's validator and posted to Learning Locker's own
# xAPI statement service, both from the npm registry (tests/xapi/package-lock.json).
add_test(NAME cli.lrs COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_lrs_cli.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} --node-dir ${CMAKE_CURRENT_BINARY_DIR}/xapi-node)
set_tests_properties(cli.lrs PROPERTIES TIMEOUT 600 SKIP_RETURN_CODE 77)
