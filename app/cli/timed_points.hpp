#pragma once
// `t,x,y,z` files: a scripted trajectory (simulate --trajectory) or a trainee's marks
// (simulate --marks). Shared by the command and its fuzz target.
#include <string>

#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/csv.hpp"

namespace palpa::cli {

enum class TimeOrder {
  Increasing,     ///< a trajectory: times strictly increase, at least two rows
  NotDecreasing,  ///< marks: several may share a time
};

/// The rows of a t,x,y,z table (t >= 0, in `order`); throws io::CsvError naming `name` and
/// the file line ("NAME: line N: column t: times must increase and be >= 0").
engine::Trajectory timed_points(const io::NumericTable& table, const std::string& name, TimeOrder order);

}  // namespace palpa::cli
