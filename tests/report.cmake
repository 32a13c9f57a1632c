# Test targets of the report module (included by tests/CMakeLists.txt).
