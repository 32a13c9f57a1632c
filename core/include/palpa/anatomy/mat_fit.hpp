#pragma once
// The MAT body of tissue lying on a support, fitted to its two surfaces
// (docs/anatomy-import.md, "The fitting method"). The skeleton points sit on a regular
// grid over the support's plane; at each grid site the skeleton's height and the medial
// radius are solved so that the paper's contours, skeleton +- radius * skeleton normal
// (section 2.1), land on the free surface and on the support, the normal taken from the
// interpolated skeleton itself. The midpoint of the two surfaces only starts the iterations:
// it is exact only where the surfaces mirror each other across a flat skeleton.
#include <string>
#include <vector>

#include "palpa/anatomy/height_field.hpp"
#include "palpa/mat/body_grid.hpp"

namespace palpa::anatomy {

/// How far one fitted contour is from its input surface (m), sampled densely over the
/// contour (8 points per grid interval each way).
struct SurfaceError {
  double max = 0.0;           ///< everywhere
  double rms = 0.0;           ///< everywhere
  double interior_max = 0.0;  ///< away from the rim (FitReport::rim_band)
  double interior_rms = 0.0;
  Vec3 worst = Vec3::Zero();  ///< world position (m) of the largest distance
};

struct FitReport {
  SurfaceError top;     ///< the free surface (skin)
  SurfaceError bottom;  ///< the support
  /// m: "away from the rim" means at least this far, along the support, from where the
  /// tissue's thickness reaches zero: one grid spacing or two input resolutions.
  double rim_band = 0.0;
  int iterations = 0;  ///< Newton iterations until the largest site residual fell below 0.1 um
};

struct FittedBody {
  mat::BodyGrid grid;          ///< medial and radius filled, support bottom; no tissue yet
  std::vector<double> s_sites;  ///< the rows' positions along the frame's e1 (m)
  std::vector<double> t_sites;  ///< the columns' positions along e2 (m)
  FitReport report;
};

/// m: the largest distance "away from the rim" between the fitted contours and the input
/// surfaces the grid search aims for: 0.2 mm, so that with the half voxel a label volume's
/// surface itself may be off the contours stay within half a voxel + 0.2 mm of the anatomy
/// (docs/anatomy-import.md, "Accuracy").
inline constexpr double kFitTarget = 0.2e-3;

/// Fits a rows x cols body (rows along e1) over the tissue's footprint plus one grid
/// spacing all round, so that the grid's boundary, where the radius is 0, lies outside
/// it; starting from the midpoints, or from `start` (a coarser fit of the same surfaces)
/// where given. Throws ImportError when the surfaces hold no tissue or the spline cannot
/// follow.
FittedBody fit_body(const SurfacePair& pair, int rows, int cols, const std::string& id,
                    const FittedBody* start = nullptr);

/// fit_body on grids from about 8 intervals across the body, each started from the one
/// before, refined by sqrt(2) (by 2 while the error is over 4 times the target) up to
/// 65 x 65, until the interior error meets kFitTarget or, once the points are at most 10 mm apart, two
/// finer grids in a row gain less than 10 %
/// (what is left is in the data: a feature smaller than a grid can follow, or noise); the
/// best grid tried is returned.
FittedBody fit_body_auto(const SurfacePair& pair, const std::string& id);

}  // namespace palpa::anatomy
