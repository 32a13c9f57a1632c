# Sources of core/live: the live trainee exercise under the GUI (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/display_meshes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/live_coverage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/live_exercise.cpp
  ${CMAKE_CURRENT_LIST_DIR}/press_control.cpp
  ${CMAKE_CURRENT_LIST_DIR}/stroke_trace.cpp
  ${CMAKE_CURRENT_LIST_DIR}/felt_path.cpp
)
