# Sources of core/anatomy: cases from segmented anatomy (label volumes, surface meshes) by a
# least-squares MAT fit (docs/anatomy-import.md; see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/label_volume.cpp
  ${CMAKE_CURRENT_LIST_DIR}/label_table.cpp
  ${CMAKE_CURRENT_LIST_DIR}/builtin_tables.cpp
  ${CMAKE_CURRENT_LIST_DIR}/height_field.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mat_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fit_measure.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheet.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sheet_solver.cpp
  ${CMAKE_CURRENT_LIST_DIR}/support_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/voxel_sampler.cpp
  ${CMAKE_CURRENT_LIST_DIR}/volume_surfaces.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_columns.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_surfaces.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lesions.cpp
  ${CMAKE_CURRENT_LIST_DIR}/column_tissue.cpp
  ${CMAKE_CURRENT_LIST_DIR}/import.cpp
  ${CMAKE_CURRENT_LIST_DIR}/case_builder.cpp
)
