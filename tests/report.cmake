# Test targets of the report module (included by tests/CMakeLists.txt).
add_executable(report_tests
  report/encoding_test.cpp
  report/csv_xapi_test.cpp
  report/images_test.cpp
  report/html_test.cpp
  report/learning_curve_test.cpp
)
target_link_libraries(report_tests PRIVATE palpa_report opencv_imgproc opencv_imgcodecs GTest::gtest GTest::gtest_main)
target_compile_definitions(report_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(report_tests)
gtest_discover_tests(report_tests TEST_PREFIX "report." DISCOVERY_TIMEOUT 60)
