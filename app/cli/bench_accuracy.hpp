#pragma once
// palpa-cli bench accuracy: run time per foot-point query against its error, for the
// paper's bisection at k = 6..20 levels and the fast method cold and warm, on bodies
// chosen to be easy and hard for the bisection (flat, curved, concave, wavy).
#include <filesystem>
#include <string>
#include <vector>

namespace palpa::cli {

struct AccuracyOptions {
  int probes = 2000;
  unsigned seed = 1;
  std::filesystem::path out = "bench-results";
};

struct AccuracyRow {
  std::string body;
  std::string method;  ///< "bisect", "fast-cold", "fast-warm"
  int levels = 0;      ///< bisection levels k (0 for the fast method)
  int queries = 0;
  double ns_per_query = 0.0;
  double depth_error_max = 0.0;     ///< m, |depth - depth_ref|
  double depth_error_median = 0.0;  ///< m
  double param_error_max = 0.0;     ///< max(|u - u_ref|, |v - v_ref|)
  int inside_wrong = 0;             ///< probes whose inside/outside answer differs from the reference
};

/// Runs the sweep; writes accuracy.csv and accuracy.png into options.out and returns the rows.
std::vector<AccuracyRow> run_accuracy_benchmark(const AccuracyOptions& options);

}  // namespace palpa::cli
