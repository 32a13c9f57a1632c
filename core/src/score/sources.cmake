# Sources of core/score (see core/CMakeLists.txt).
