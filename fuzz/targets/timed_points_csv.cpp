// Fuzz target: a `t,x,y,z` CSV as simulate reads its --trajectory and --marks files.
// Every accepted table has finite values and times in the order asked for.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "timed_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using palpa::cli::TimeOrder;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  palpa::io::NumericTable table;
  try {
    table = palpa::io::parse_numeric_csv(in, "fuzz.csv", {"t", "x", "y", "z"});
  } catch (const palpa::io::CsvError&) {
    return 0;
  }
  for (const auto order : {TimeOrder::Increasing, TimeOrder::NotDecreasing}) {
    try {
      const auto points = palpa::cli::timed_points(table, "fuzz.csv", order);
      if (points.t.size() != points.position.size()) std::abort();
      for (std::size_t k = 0; k < points.t.size(); ++k) {
        if (!std::isfinite(points.t[k]) || points.t[k] < 0.0 || !points.position[k].allFinite()) std::abort();
        if (k > 0 && (order == TimeOrder::Increasing ? points.t[k] <= points.t[k - 1] : points.t[k] < points.t[k - 1])) {
          std::abort();
        }
      }
    } catch (const palpa::io::CsvError&) {
    }
  }
  return 0;
}
