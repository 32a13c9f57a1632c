#pragma once
// How closely a fitted body reproduces its data at the data sites (an interpolant must
// pass through them; this measures by how much round-off it misses).
#include <array>

#include "palpa/mat/body_grid.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::mat {

struct FitResidual {
  /// max over the data sites of |SK(u_i, v_j) - data| per skeleton channel (SI units).
  std::array<double, kSkeletonChannels> skeleton{};
  double top = 0.0;     ///< max distance (m) of the top contour from R = P + rN at the sites
  double bottom = 0.0;  ///< max distance (m) of the bottom contour from S = P - rN
};

FitResidual fit_residual(const MatBody& body, const BodyGrid& grid, const MaterialDefaults& defaults = {});

}  // namespace palpa::mat
