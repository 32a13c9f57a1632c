# Sources of core/exercise (see core/CMakeLists.txt).
