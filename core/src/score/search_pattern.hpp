#pragma once
// Search-pattern measures of the contact path over the top contour (docs/scoring.md,
// "Search pattern"), after the classes of Azari et al. 2015.
#include <vector>

#include "contour_grid.hpp"
#include "palpa/score/score.hpp"

namespace palpa::score::detail {

/// A point of the contact path, kept when the contact moved >= 0.5 mm (so tremor and a
/// held press add no length). `piece` changes when contact is lost or changes body.
struct PathPoint {
  int body = 0;
  int piece = 0;
  double u = 0.0, v = 0.0;
  Vec3 top = Vec3::Zero();
  bool revisit = false;  ///< the contact's cell had been covered on an earlier pass
};

/// Path length, strip fraction, strip spacing and revisit fraction of `path`
/// (`kind` and `efficiency` are left for classify). `grids` give each body's lengths.
SearchPattern measure_pattern(const std::vector<PathPoint>& path, const std::vector<const ContourGrid*>& grids,
                              double pad_radius);

/// The class from the measures, the coverage and whether the covered area is compact.
PatternKind classify_pattern(const SearchPattern& pattern, bool any_contact, double coverage, bool compact,
                             const Thresholds& thresholds);

}  // namespace palpa::score::detail
