# Compiles through ccache when it is installed (PALPA_CCACHE=OFF to turn it off).
# base_dir makes the cache independent of where the tree is checked out (a CI clone in
# another folder hits the entries a developer's build left), and hash_dir off lets -g builds
# of two checkouts share entries too (their debug info then names the first checkout's folder).
option(PALPA_CCACHE "Compile through ccache when it is installed" ON)
find_program(PALPA_CCACHE_PROGRAM ccache)
if(PALPA_CCACHE AND PALPA_CCACHE_PROGRAM)
  set(launcher ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=1
      CCACHE_SLOPPINESS=pch_defines,time_macros ${PALPA_CCACHE_PROGRAM})
  set(CMAKE_C_COMPILER_LAUNCHER ${launcher})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${launcher})
  message(STATUS "Compiler cache: ${PALPA_CCACHE_PROGRAM}")
endif()
