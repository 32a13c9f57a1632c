# Test targets of the session module (included by tests/CMakeLists.txt).
