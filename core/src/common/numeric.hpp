#pragma once
// Small numeric helpers the core's sources share (internal: not installed).
#include <cstddef>

namespace palpa {

/// A non-negative int as an index: spline and grid code counts in int (degrees, spans)
/// and indexes std::vector with size_t; this says the conversion is intended.
constexpr std::size_t idx(int i) { return static_cast<std::size_t>(i); }

/// x clamped to [0, 1]; a NaN stays NaN (std::clamp would be undefined for it).
constexpr double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

}  // namespace palpa
