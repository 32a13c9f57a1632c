# The application's window management (app/gui/app_windows) and the shared File menu,
# under Xvfb like the other window tests.
add_executable(ui_app_tests
  ui/app_windows_test.cpp
  ${PROJECT_SOURCE_DIR}/app/gui/app_windows.cpp  # the code under test, from the application
  ${PROJECT_SOURCE_DIR}/app/gui/gui_device.cpp
  ${PROJECT_SOURCE_DIR}/app/gui/session_upload.cpp
)
set_target_properties(ui_app_tests PROPERTIES AUTOMOC ON)
target_include_directories(ui_app_tests PRIVATE ${PROJECT_SOURCE_DIR}/app/gui)
target_link_libraries(ui_app_tests PRIVATE palpa_ui palpa_device palpa_store palpa_lrs Qt5::Test Qt5::Network)
target_compile_definitions(ui_app_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
vtk_module_autoinit(TARGETS ui_app_tests MODULES ${VTK_LIBRARIES})
palpa_warnings(ui_app_tests)
add_test(NAME ui.app COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_app_tests>)
palpa_gui_sanitizer_env(ui.app)

# SIGTERM / SIGINT mid-exercise: the window closes normally and the session is finished.
add_test(NAME ui.signal COMMAND ${PALPA_XVFB_RUN} -a ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/ui/test_gui_signal.py
         --gui $<TARGET_FILE:palpa> --cli ${cli})
if(PALPA_SANITIZE)
  set_tests_properties(ui.signal PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")
endif()
