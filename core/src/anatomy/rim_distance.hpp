#pragma once
// Internal to core/anatomy: how a fit is measured against its input surfaces.
#include "palpa/anatomy/mat_fit.hpp"

namespace palpa::anatomy {

/// m per sample of pair.top: the distance along the support to the nearest sample on the
/// other side of the rim (where the tissue's thickness crosses half a resolution), by a
/// two-pass chamfer transform (within 4 % of the Euclidean distance).
std::vector<double> rim_distance(const SurfacePair& pair);

/// Fills fitted.report (top, bottom) by sampling both contours of the fitted body 8 times
/// per grid interval each way. Throws ImportError when the spline cannot fit the grid.
void measure_fit(const SurfacePair& pair, FittedBody& fitted);

}  // namespace palpa::anatomy
