#pragma once
// palpa-cli bench table1: scenes like the paper's Table 1, measured as the paper did
// (preprocessing, memory, haptic rate with and without dynamics) and then some.
#include <filesystem>
#include <optional>

#include "palpa/engine/engine.hpp"

namespace palpa::cli {

struct Table1Options {
  std::optional<std::filesystem::path> csv;  ///< --csv OUT
  double seconds = 2.0;                      ///< simulated seconds of palpation per scene and mode
  double realtime_seconds = 2.0;             ///< then each scene paced at 1 kHz on the real-time loop (0: skip)
  bool load = false;                         ///< keep every other core busy during the paced runs
  double display_span = engine::kDisplaySpan; ///< m, the drawn nets' refinement (0: the fitted nets)
  /// --tissue kpa: each body given by the Young's modulus that derives its stiffness under
  /// the calibrated law (the same N/m at every point), so the tick runs that law.
  bool tissue_in_pa = false;
  bool finger = false;  ///< --indenter finger (with --tissue kpa): the rounded finger's force
};

int run_bench_table1(const Table1Options& options);

}  // namespace palpa::cli
