# Sources of core/render: tessellation for display, frustum culling, level of detail, surface picks (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/tessellation_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tessellation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frustum.cpp
  ${CMAKE_CURRENT_LIST_DIR}/level_of_detail.cpp
  ${CMAKE_CURRENT_LIST_DIR}/surface_pick.cpp
)
