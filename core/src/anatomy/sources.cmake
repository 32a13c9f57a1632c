# Sources of core/anatomy: cases from segmented anatomy (label volumes, surface meshes) by a
# least-squares MAT fit (docs/anatomy-import.md; see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/label_volume.cpp
)
