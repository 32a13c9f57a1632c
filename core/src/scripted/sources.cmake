# Sources of core/scripted (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/tumour_placement.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scripted_trainee.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exercise.cpp
)
