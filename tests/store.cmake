# The centre store (store/, docs/centre.md) against a throwaway PostgreSQL server
# (tests/tools/pg_test_server.py). Under CI=true a server that cannot start fails the tests;
# elsewhere they skip when PostgreSQL is not installed.
foreach(name schema push workers e2e hostile hostile_queue)
  add_test(NAME cli.store_${name} COMMAND ${PALPA_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/test_store_${name}.py
           --cli ${cli} --repo ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.store_${name} PROPERTIES TIMEOUT 600 LABELS store)
endforeach()
