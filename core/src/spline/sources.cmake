# Sources of core/spline: B-spline bases, curves and surfaces, interpolation, knot refinement (The NURBS Book) (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/basis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/knot_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bspline_curve.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bspline_surface.cpp
  ${CMAKE_CURRENT_LIST_DIR}/banded_lu.cpp
  ${CMAKE_CURRENT_LIST_DIR}/interpolation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/knot_refinement.cpp
)
