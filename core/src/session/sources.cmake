# Sources of core/session (see core/CMakeLists.txt).
