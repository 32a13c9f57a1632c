#pragma once
// Nearest-point distances between two point sets, for the search pattern's strip spacing
// (docs/scoring.md, "Search pattern"): exact, with a k-d tree (nanoflann) over the second
// set, so that a session's strips cost O(n log n) rather than one comparison per pair of
// points (a hostile session can put hundreds of thousands of points in two strips).
#include <vector>

#include "palpa/vec3.hpp"

namespace palpa::score {

/// For every point of `from`, the distance to the nearest point of `to` (m, in order);
/// empty when `to` has no finite point. Points that are not finite are left out of `to`
/// and get NaN in `from`. Copies count once: the work is O(n log n) in the distinct points.
std::vector<double> nearest_distances(const std::vector<Vec3>& from, const std::vector<Vec3>& to);

}  // namespace palpa::score
