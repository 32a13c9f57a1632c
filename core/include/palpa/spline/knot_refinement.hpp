#pragma once
// Knot refinement (The NURBS Book, Piegl & Tiller, 2nd ed., section 5.3, A5.4
// RefineKnotVectCurve and its surface form RefineKnotVectSurface): inserting knots
// changes the control net, not the surface. Palpa refines the drawn contours for display
// so that the paper's control-point modification (section 3.3) moves a patch the size of a
// fingertip instead of a fifth of the body.
#include <span>
#include <vector>

#include "palpa/spline/bspline_surface.hpp"

namespace palpa::spline {

enum class Direction { U, V };

/// A5.4 in one parameter direction: the same surface with the knots `insert` (sorted,
/// inside the knot range; repeats allowed up to the degree) added along `direction`.
/// Every channel of the control points is refined alike.
BSplineSurface refine_knots(const BSplineSurface& surface, Direction direction, std::span<const double> insert);

/// Knots that split every non-empty span of `knots` into `pieces[k]` equal parts (pieces
/// has one entry per non-empty span, in order; 1 leaves a span whole).
std::vector<double> split_spans(const std::vector<double>& knots, std::span<const int> pieces);

}  // namespace palpa::spline
