# Tests of the application window (QtTest), run under Xvfb with Mesa's software OpenGL
# (included by tests/CMakeLists.txt when PALPA_BUILD_GUI is on).
find_program(PALPA_XVFB_RUN xvfb-run REQUIRED)

# A QtTest executable over palpa_ui: moc, Qt Test, the source tree's path, VTK's modules.
function(palpa_qt_test target)
  add_executable(${target} ${ARGN})
  set_target_properties(${target} PROPERTIES AUTOMOC ON)
  target_link_libraries(${target} PRIVATE palpa_ui Qt5::Test)
  target_compile_definitions(${target} PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  vtk_module_autoinit(TARGETS ${target} MODULES ${VTK_LIBRARIES})
  palpa_warnings(${target})
endfunction()

# Under the dev-gui preset the GUI runs with AddressSanitizer and UBSan, but without
# LeakSanitizer: D-Bus (Qt's platform integration) and a library Mesa unloads leave a few
# small blocks at exit (1144 bytes in 3 allocations, none from Palpa), and the indirect ones
# come from an unloaded module that no suppression can name.
function(palpa_gui_sanitizer_env)
  if(PALPA_SANITIZE)
    set_tests_properties(${ARGN} PROPERTIES ENVIRONMENT
                         "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
  endif()
endfunction()

palpa_qt_test(ui_tests ui/trainee_window_test.cpp)
target_compile_definitions(ui_tests PRIVATE PALPA_GUI_EXE="$<TARGET_FILE:palpa>")
add_dependencies(ui_tests palpa)  # the command-line and screenshot tests run the application
add_test(NAME ui.trainee COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_tests>)
palpa_gui_sanitizer_env(ui.trainee)

# What the trainee sees besides the body: the push-back trace and the finger that sticks on
# a lump, the coverage overlay's dots thinned for the view, and the bodies' level of detail.
palpa_qt_test(ui_feel_tests ui/push_back_feel_test.cpp ui/coverage_overlay_test.cpp ui/level_of_detail_test.cpp)
add_test(NAME ui.feel COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_feel_tests>)
palpa_gui_sanitizer_env(ui.feel)

# Acceptance: palpation through the window's own input events, checked against fresh
# presses, and a mouse trainee that must pass the default case (long form: PALPA_LONG_TESTS=1).
palpa_qt_test(ui_acceptance_tests ui/palpation_acceptance_test.cpp ui/person_trainee.cpp ui/person_trainee.hpp
              ui/acceptance_cases.hpp)
if(PALPA_SANITIZE)
  # Under the sanitizers the window draws several times slower than a person moves: the
  # window's keys, force mode, gauge and close question run there; the slides and the mouse
  # exams, whose checks assume the finger keeps pace with the pointer, run in the release
  # build (ui.trainee exercises the same palpation code under the sanitizers).
  add_test(NAME ui.acceptance COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           keysWorkAsSoonAsTheWindowIsActive theGaugeNeverOverlapsDownToTheMinimumSize
           closingAsksAndAnAbandonedAttemptIsStoredAsSuch)
  set_tests_properties(ui.acceptance PROPERTIES ENVIRONMENT
                       "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
else()
  # The exams run in real time (a minute or two each): split so that ctest runs them side
  # by side and none comes near the per-test timeout. Ladder-4 (a mass the palpability check
  # warns about) runs in the long form only: the whole binary with PALPA_LONG_TESTS=1.
  add_test(NAME ui.acceptance COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           keysWorkAsSoonAsTheWindowIsActive theGaugeNeverOverlapsDownToTheMinimumSize
           closingAsksAndAnAbandonedAttemptIsStoredAsSuch slidesOnTheDefaultBreast slidesOnTheTwoDomes
           aMouseTraineePassesTheDefaultCase aMouseTraineeWithLightPressureOnlyFailsDeepCoverage)
  add_test(NAME ui.acceptance.ladders COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           aMouseTraineePassesEveryBundledCase:ladder-1.json aMouseTraineePassesEveryBundledCase:ladder-2.json
           aMouseTraineePassesEveryBundledCase:ladder-3.json)
  add_test(NAME ui.acceptance.hard COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           "aMouseTraineePassesEveryBundledCase:two tumours" "aMouseTraineePassesEveryBundledCase:no tumour")
  add_test(NAME ui.acceptance.anatomy COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           "aMouseTraineePassesEveryBundledCase:victre-breast.json")
  add_test(NAME ui.acceptance.limits COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_acceptance_tests>
           everyStepAtEverySpotStaysUnderTheSafetyLimit aMouseTraineePassesWithAStallingDevice)
  set_tests_properties(ui.acceptance ui.acceptance.ladders ui.acceptance.hard ui.acceptance.anatomy ui.acceptance.limits
                     PROPERTIES TIMEOUT 1200)
endif()

# Review mode: replays data/sessions/expert.palpa (and sloppy.palpa for a failed score).
add_executable(ui_review_tests
  ui/review_window_test.cpp
)
set_target_properties(ui_review_tests PROPERTIES AUTOMOC ON)
target_link_libraries(ui_review_tests PRIVATE palpa_ui Qt5::Test)
target_compile_definitions(ui_review_tests PRIVATE PALPA_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                   PALPA_GUI_EXE="$<TARGET_FILE:palpa>"
                                                   PALPA_CLI_EXE="$<TARGET_FILE:palpa-cli>")
vtk_module_autoinit(TARGETS ui_review_tests MODULES ${VTK_LIBRARIES})
palpa_warnings(ui_review_tests)
add_dependencies(ui_review_tests palpa palpa-cli)
add_test(NAME ui.review COMMAND ${PALPA_XVFB_RUN} -a $<TARGET_FILE:ui_review_tests>)
if(PALPA_SANITIZE)
  set_tests_properties(ui.review PROPERTIES ENVIRONMENT
                       "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
endif()

# palpa --bench on the smallest Table 1 scenes: rows, frames, deformation, haptic ticks (no timing thresholds).
add_test(NAME ui.frame_bench COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/ui/test_frame_bench.py
         --gui $<TARGET_FILE:palpa> --xvfb-run ${PALPA_XVFB_RUN})
if(PALPA_SANITIZE)
  set_tests_properties(ui.frame_bench PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")
endif()
