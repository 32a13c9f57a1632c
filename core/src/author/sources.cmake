# Sources of core/author: the headless model under the instructor window (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/presets.cpp
  ${CMAKE_CURRENT_LIST_DIR}/stiffness_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/case_draft.cpp
  ${CMAKE_CURRENT_LIST_DIR}/palpability.cpp
  ${CMAKE_CURRENT_LIST_DIR}/problem_text.cpp
)
