# Instructor mode (the authoring window, QtTest under Xvfb; included by tests/CMakeLists.txt
# when PALPA_BUILD_GUI is on, after ui.cmake, which finds xvfb-run).
add_executable(ui_instructor_tests
  ui/instructor_window_test.cpp
  ui/import_anatomy_test.cpp  # Case > Import anatomy…, run from the same main
)
set_target_properties(ui_instructor_tests PROPERTIES AUTOMOC ON)
target_link_libraries(ui_instructor_tests PRIVATE palpa_ui palpa_anatomy_io Qt5::Test)
target_compile_definitions(ui_instructor_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                       PALPA_GUI_EXE="$<TARGET_FILE:palpa>")
vtk_module_autoinit(TARGETS ui_instructor_tests MODULES ${VTK_LIBRARIES})
palpa_warnings(ui_instructor_tests)
add_dependencies(ui_instructor_tests palpa)  # the screenshot test runs the application
add_test(NAME ui.instructor COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_instructor_tests>)
if(PALPA_SANITIZE)
  # As ui.trainee: ASan and UBSan, without LeakSanitizer (D-Bus and Mesa leave blocks at exit).
  set_tests_properties(ui.instructor PROPERTIES ENVIRONMENT
                       "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
endif()
