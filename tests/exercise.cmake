# Test targets of the exercise module (included by tests/CMakeLists.txt).
