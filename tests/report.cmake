# Test targets of the report module (included by tests/CMakeLists.txt).
add_executable(report_tests
  report/encoding_test.cpp
  report/printable_test.cpp
  report/csv_xapi_test.cpp
  report/images_test.cpp
  report/html_test.cpp
  report/learning_curve_test.cpp
  report/report_json_test.cpp
  report/csv_number_test.cpp
  report/session_filter_test.cpp
)
target_link_libraries(report_tests PRIVATE palpa_report opencv_imgproc opencv_imgcodecs GTest::gtest GTest::gtest_main)
target_compile_definitions(report_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(report_tests)
gtest_discover_tests(report_tests TEST_PREFIX "report." DISCOVERY_TIMEOUT 60)

# Writes small sessions with known content for the score and batch CLI tests.
add_executable(make_test_sessions
  report/make_test_sessions.cpp
)
target_link_libraries(make_test_sessions PRIVATE palpa_core)
palpa_warnings(make_test_sessions)

add_test(NAME cli.score COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_score_cli.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} --make-sessions $<TARGET_FILE:make_test_sessions>)
# Under the sanitizers a command runs several times slower and holds more memory (shadow
# memory, quarantine): the hostile files' limits scale with --sanitized.
set(hostile_sanitized "")
if(PALPA_SANITIZE)
  set(hostile_sanitized --sanitized)
endif()
add_test(NAME cli.hostile_sessions COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_hostile_sessions.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} ${hostile_sanitized})
# Scoring reads the samples as a stream: millions of ticks in a 1 GB address space
# (PALPA_LONG_TESTS=1 adds the 72 million of a 20-hour session).
add_test(NAME cli.stream_scoring COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_stream_scoring.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} ${hostile_sanitized})
add_test(NAME cli.batch COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_batch_cli.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} --make-sessions $<TARGET_FILE:make_test_sessions>)

# A batch of 1000 sessions with corrupt files among them (copies of known sessions).
add_test(NAME cli.batch_1000 COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_batch_1000.py
         --cli ${cli} --repo ${PROJECT_SOURCE_DIR} --make-sessions $<TARGET_FILE:make_test_sessions>)
