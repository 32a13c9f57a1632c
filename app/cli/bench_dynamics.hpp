#pragma once
// palpa-cli bench dynamics: error against run time for the control-point springs
// (the exact integrator vs the explicit-family alternatives over a dt sweep) and for the
// p' x q' choices of control-point modification.
#include <filesystem>

namespace palpa::cli {

/// Writes dynamics.csv, dynamics.png, modification.csv into out_dir; prints tables.
int run_bench_dynamics(const std::filesystem::path& out_dir);

}  // namespace palpa::cli
