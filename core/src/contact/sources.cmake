# Sources of core/contact: foot point, penetration and force (paper section 3.1, 3.4) (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/foot_point.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact.cpp
  ${CMAKE_CURRENT_LIST_DIR}/column.cpp
  ${CMAKE_CURRENT_LIST_DIR}/force.cpp
  ${CMAKE_CURRENT_LIST_DIR}/finger.cpp
)
