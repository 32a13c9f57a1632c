# Tests of the application window (QtTest), run under Xvfb with Mesa's software OpenGL
# (included by tests/CMakeLists.txt when PALPA_BUILD_GUI is on).
find_program(PALPA_XVFB_RUN xvfb-run REQUIRED)
add_executable(ui_tests ui/trainee_window_test.cpp)
set_target_properties(ui_tests PROPERTIES AUTOMOC ON)
target_link_libraries(ui_tests PRIVATE palpa_ui Qt5::Test)
target_compile_definitions(ui_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                            PALPA_GUI_EXE="$<TARGET_FILE:palpa>")
vtk_module_autoinit(TARGETS ui_tests MODULES ${VTK_LIBRARIES})
palpa_warnings(ui_tests)
add_dependencies(ui_tests palpa)  # the command-line and screenshot tests run the application
add_test(NAME ui.trainee COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_tests>)
