# Sources of core/session (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/session_id.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sqlite_util.cpp
  ${CMAKE_CURRENT_LIST_DIR}/checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sample_blocks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/compaction.cpp
  ${CMAKE_CURRENT_LIST_DIR}/file_claim.cpp
  ${CMAKE_CURRENT_LIST_DIR}/session_writer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/hot_journal.cpp
  ${CMAKE_CURRENT_LIST_DIR}/session_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/session_recorder.cpp
  ${CMAKE_CURRENT_LIST_DIR}/session_upgrade.cpp
  ${CMAKE_CURRENT_LIST_DIR}/replay.cpp
)
