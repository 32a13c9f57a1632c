# Test targets of the device layer (device/; included by tests/CMakeLists.txt). No hardware:
# recorded HID reports, a fake Falcon on a fake USB transport, fake enumerations.
add_executable(device_tests
  device/spacemouse_test.cpp
  device/falcon_protocol_test.cpp
  device/falcon_fault_test.cpp
  device/falcon_kinematics_test.cpp
  device/registry_replay_test.cpp
  device/fallback_test.cpp
)
target_link_libraries(device_tests PRIVATE palpa_device palpa_core GTest::gtest GTest::gtest_main)
target_compile_definitions(device_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
palpa_warnings(device_tests)
palpa_test_pch(device_tests)
gtest_discover_tests(device_tests TEST_PREFIX "device." DISCOVERY_TIMEOUT 60)

# read()/write_force() in the haptic thread allocate nothing (counting operator new of its own).
add_executable(device_alloc_test
  device/device_alloc_test.cpp
)
target_link_libraries(device_alloc_test PRIVATE palpa_device palpa_core GTest::gtest GTest::gtest_main)
palpa_warnings(device_alloc_test)
palpa_test_pch(device_alloc_test)
gtest_discover_tests(device_alloc_test TEST_PREFIX "device." DISCOVERY_TIMEOUT 60)

# Every USB id the drivers know has a udev rule.
add_test(NAME device.udev_rules COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/device/test_udev_rules.py
         --repo ${PROJECT_SOURCE_DIR})
# palpa-cli devices lists the virtual device and never fails for want of /dev/bus/usb.
add_test(NAME cli.devices COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_devices_cli.py --cli ${cli}
         --repo ${PROJECT_SOURCE_DIR})
