# Sources of core/mat: the MAT body model: fitting the skeleton, layer stiffness, tissue materials (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/mat_body.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fit_residual.cpp
  ${CMAKE_CURRENT_LIST_DIR}/layer_stiffness.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tissue_materials.cpp
)
