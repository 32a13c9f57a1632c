# Packaging and install, included by tests/CMakeLists.txt.

# Where the bundled data is found at run time (core io/data_paths).
add_executable(data_paths_tests
  packaging/data_paths_test.cpp
)
target_link_libraries(data_paths_tests PRIVATE palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(data_paths_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(data_paths_tests)
palpa_test_pch(data_paths_tests)
gtest_discover_tests(data_paths_tests TEST_PREFIX "core." DISCOVERY_TIMEOUT 60)

# The .deb (cpack into a temporary folder, unpacked into a scratch root, run from there) and
# the installed CMake package (cmake --install, examples/consumer built against it). They
# reuse the built binaries; under the dev preset (ASan) they skip with a message.
set(packaging_sanitized)
if(PALPA_SANITIZE)
  set(packaging_sanitized --sanitized)
endif()
set(packaging_gui)
if(NOT PALPA_BUILD_GUI)
  set(packaging_gui --no-gui)
endif()
add_test(NAME packaging.deb COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/packaging/test_deb.py
         --build-dir ${PROJECT_BINARY_DIR} --source-dir ${PROJECT_SOURCE_DIR} --version ${PROJECT_VERSION}
         --cpack ${CMAKE_CPACK_COMMAND} ${packaging_sanitized} ${packaging_gui})
add_test(NAME packaging.consumer COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/packaging/test_consumer.py
         --build-dir ${PROJECT_BINARY_DIR} --source-dir ${PROJECT_SOURCE_DIR} --version ${PROJECT_VERSION}
         --cmake ${CMAKE_COMMAND} --generator ${CMAKE_GENERATOR} --cxx ${CMAKE_CXX_COMPILER} ${packaging_sanitized})
# Both install the whole build tree; one at a time keeps them off each other's feet and
# leaves a core for the rest of the suite.
set_tests_properties(packaging.deb packaging.consumer PROPERTIES SKIP_RETURN_CODE 77 RESOURCE_LOCK palpa_install
                     TIMEOUT 600 LABELS packaging)
