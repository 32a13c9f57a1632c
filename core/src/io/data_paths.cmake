# core/io/data_paths (see core/CMakeLists.txt): the run-time lookup of the bundled data.
# The build tree's location is compiled in so that a program running from the build tree
# (and only from there) falls back to the source tree's data/.
target_sources(palpa_core PRIVATE ${CMAKE_CURRENT_LIST_DIR}/data_paths.cpp)
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/data_paths.cpp PROPERTIES COMPILE_DEFINITIONS
  "PALPA_BUILD_TREE_DIR=\"${PROJECT_BINARY_DIR}\";PALPA_SOURCE_DATA_DIR=\"${PROJECT_SOURCE_DIR}/data\"")
