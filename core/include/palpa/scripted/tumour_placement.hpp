#pragma once
// Randomized tumour placement (docs/case-format.md, "Tumours"): a tumour with a
// "placement" rule gets a new centre for each seeded exercise, drawn uniformly in a
// (u, v) rectangle of its body's skeleton parameters and at a depth fraction of the local
// tissue thickness below the top contour. The draw is the same on every platform.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::scripted {

/// A tumour's randomization rule: closed ranges within [0, 1].
struct Placement {
  std::array<double, 2> u{0.0, 1.0};
  std::array<double, 2> v{0.0, 1.0};
  /// Fraction d of the local thickness 2R below the top contour:
  /// centre = top(u, v) - d * 2R * N, so d = 0.5 lies on the skeleton.
  std::array<double, 2> depth{0.5, 0.5};
};

/// The rule of tumour `index` of a parsed case (from its document, which parse_case has
/// validated), or nothing when it has none.
std::optional<Placement> placement_of(const io::CaseFile& file, std::size_t index);

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny generator with a fixed output on every
/// platform, unlike std::uniform_*_distribution.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1): the top 53 bits as a double.
  double uniform() noexcept { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi].
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

/// Draws up to this many centres per tumour before giving up.
inline constexpr int kMaxPlacementDraws = 200;

/// The case with every tumour that has a placement rule moved to a centre drawn with
/// `seed` (rejection sampling until the sphere lies inside its body and overlaps no other
/// tumour), in `tumours` and in `document`, so io::to_json gives the placed case. Tumours
/// without a rule keep their centre. Throws io::CaseError naming `source`: a body that
/// cannot be fitted, or /tumors/K/placement when no valid centre was found.
io::CaseFile place_tumours(const io::CaseFile& file, std::uint64_t seed, const std::string& source,
                           const mat::FitOptions& options = {});

}  // namespace palpa::scripted
