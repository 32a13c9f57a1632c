# Sources of core/engine: devices, the haptic tick, the real-time loop, snapshots (see core/CMakeLists.txt).
target_sources(palpa_core PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/virtual_device.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fallback_device.cpp
  ${CMAKE_CURRENT_LIST_DIR}/stalling_device.cpp
  ${CMAKE_CURRENT_LIST_DIR}/force_governor.cpp
  ${CMAKE_CURRENT_LIST_DIR}/engine.cpp
  ${CMAKE_CURRENT_LIST_DIR}/loop_stats.cpp
  ${CMAKE_CURRENT_LIST_DIR}/realtime_loop.cpp
  ${CMAKE_CURRENT_LIST_DIR}/scene_snapshot.cpp
  ${CMAKE_CURRENT_LIST_DIR}/drawn_scene.cpp
)
