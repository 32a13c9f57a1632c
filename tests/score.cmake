# Test targets of the score module (included by tests/CMakeLists.txt).
