# Test targets of anatomy_io (label volumes and meshes through VTK; included by
# tests/CMakeLists.txt). Built with or without the GUI.
add_executable(anatomy_io_tests
  anatomy_io/support.cpp
  anatomy_io/volume_test.cpp
  anatomy_io/refusal_test.cpp
  anatomy_io/mesh_test.cpp
  anatomy_io/vtk_interop_test.cpp
  anatomy_io/import_request_test.cpp
)
# VTK's NIfTI writer (IOImage, found at the top level) as an independent writer of the files
# the reader reads.
target_link_libraries(anatomy_io_tests PRIVATE palpa_anatomy_io palpa_core VTK::IOImage VTK::CommonCore
                      VTK::CommonDataModel VTK::CommonMath GTest::gtest GTest::gtest_main)
palpa_warnings(anatomy_io_tests)
gtest_discover_tests(anatomy_io_tests TEST_PREFIX "anatomy_io." DISCOVERY_TIMEOUT 60)
