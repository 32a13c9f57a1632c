#pragma once
// The schema's migrations in order: migrations()[0] takes an empty database to version 1,
// migrations()[k] takes version k to k + 1. Append new ones; never edit a released one.
#include <string>
#include <vector>

namespace palpa::store {

const std::vector<const char*>& migrations();

/// Version 3 (migrations_v3.cpp).
const std::string& migration_v3();

}  // namespace palpa::store
