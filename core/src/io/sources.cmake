# Sources of core/io: case files, CSV and JSON text, scoring thresholds (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/json_text.cpp
  ${CMAKE_CURRENT_LIST_DIR}/case_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/csv.cpp
  ${CMAKE_CURRENT_LIST_DIR}/thresholds.cpp
  ${CMAKE_CURRENT_LIST_DIR}/training.cpp
)

# data_paths: the run-time lookup of the bundled data.
# The build tree's location is compiled in so that a program running from the build tree
# (and only from there) falls back to the source tree's data/.
target_sources(palpa_core PRIVATE ${CMAKE_CURRENT_LIST_DIR}/data_paths.cpp)
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/data_paths.cpp PROPERTIES COMPILE_DEFINITIONS
  "PALPA_BUILD_TREE_DIR=\"${PROJECT_BINARY_DIR}\";PALPA_SOURCE_DATA_DIR=\"${PROJECT_SOURCE_DIR}/data\"")
