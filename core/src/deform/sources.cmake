# Sources of core/deform: control-point modification and the springs (paper sections 3.2, 3.3) (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/oscillator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/control_point_modification.cpp
  ${CMAKE_CURRENT_LIST_DIR}/deformed_body.cpp
)
