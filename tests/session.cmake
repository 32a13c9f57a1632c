# Test targets of the session module (included by tests/CMakeLists.txt).
find_package(SQLite3 REQUIRED)  # the tests damage session files on purpose, through SQLite
add_executable(session_tests
  core/session/session_roundtrip_test.cpp
  core/session/session_crash_test.cpp
  core/session/session_claim_test.cpp
  core/session/session_corrupt_test.cpp
  core/session/session_recorder_test.cpp
  core/session/session_snapshot_test.cpp
  core/session/session_replay_test.cpp
  core/session/session_format2_test.cpp
  core/session/session_stream_test.cpp
  core/session/session_id_test.cpp
)
target_link_libraries(session_tests PRIVATE palpa_core SQLite::SQLite3 GTest::gtest GTest::gtest_main)
target_compile_definitions(session_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(session_tests)
palpa_test_pch(session_tests)
gtest_discover_tests(session_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)

if(PALPA_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
  add_executable(session_bench
    bench/session_bench.cpp
  )
  target_link_libraries(session_bench PRIVATE palpa_core benchmark::benchmark)
  target_compile_definitions(session_bench PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  palpa_warnings(session_bench)
endif()

# A finished session read with nothing but Python's standard sqlite3 module.
add_executable(session_example
  core/session/session_example_main.cpp
)
target_link_libraries(session_example PRIVATE palpa_core fmt::fmt)
palpa_warnings(session_example)
add_test(NAME cli.session_python COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_session_python.py
         --example $<TARGET_FILE:session_example> --repo ${PROJECT_SOURCE_DIR} --cli ${cli})

# palpa-cli session upgrade: format-1 files to format 2, checked against their scores.
add_test(NAME cli.session_upgrade COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_session_upgrade.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR})
