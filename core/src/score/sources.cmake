# Sources of core/score (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/contour_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/coverage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/search_pattern.cpp
  ${CMAKE_CURRENT_LIST_DIR}/nearest_distance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/marks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/timeline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exam_grids.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sample_pass.cpp
  ${CMAKE_CURRENT_LIST_DIR}/figures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/verdict.cpp
  ${CMAKE_CURRENT_LIST_DIR}/score.cpp
  ${CMAKE_CURRENT_LIST_DIR}/score_json.cpp
  ${CMAKE_CURRENT_LIST_DIR}/score_from_json.cpp
)
