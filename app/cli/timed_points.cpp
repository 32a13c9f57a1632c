#include "timed_points.hpp"

#include <fmt/format.h>

namespace palpa::cli {

engine::Trajectory timed_points(const io::NumericTable& table, const std::string& name, TimeOrder order) {
  const bool strictly = order == TimeOrder::Increasing;
  engine::Trajectory out;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (row.size() != 4) throw io::CsvError(name + ": expected the columns t,x,y,z");
    const bool back_in_time = !out.t.empty() && (strictly ? row[0] <= out.t.back() : row[0] < out.t.back());
    if (row[0] < 0.0 || back_in_time) {
      throw io::CsvError(fmt::format("{}: line {}: column t: times must {} and be >= 0", name, table.line_numbers[r],
                                     strictly ? "increase" : "not decrease"));
    }
    out.t.push_back(row[0]);
    out.position.emplace_back(row[1], row[2], row[3]);
  }
  if (strictly && out.t.size() < 2) throw io::CsvError(name + ": a trajectory needs at least two rows");
  return out;
}

}  // namespace palpa::cli
