#pragma once
// Internal to core/anatomy: the skeleton sheet being fitted, one (height, radius) pair per
// grid site over the support's frame, and the two equations each interior site must meet.
#include <vector>

#include "palpa/anatomy/height_field.hpp"

namespace palpa::anatomy {

struct Site {
  double m = 0.0;  ///< m: the skeleton's height along the frame's normal
  double r = 0.0;  ///< m: the medial radius
};

struct Sheet {
  std::vector<double> s, t;  ///< site positions along e1 (rows) and e2 (columns)
  std::vector<Site> sites;   ///< row-major
  int rows = 0, cols = 0;

  std::size_t at(int i, int j) const { return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(j); }
};

/// The residuals of one site with the skeleton normal nl (frame components, nl.z() > 0):
/// f1, the top contour point's height above the free surface, and f2, the bottom one's
/// above the support; d1 and d2 are their derivatives in r (in m they are 1).
struct SiteResidual {
  double f1 = 0.0, f2 = 0.0, d1 = 0.0, d2 = 0.0;
  bool ok = false;
};
SiteResidual site_residual(const SurfacePair& pair, double s, double t, const Vec3& nl, const Site& x);

/// The skeleton's world points, xyz per site (row-major).
std::vector<double> skeleton_xyz(const SurfacePair& pair, const Sheet& sheet);

/// The interpolated skeleton's unit normal at each site, in frame components.
std::vector<Vec3> site_normals(const SurfacePair& pair, const Sheet& sheet);

/// Solves the two equations of every interior site with tissue under it together, by
/// Newton's method on the sheet's heights and radii (one square sparse system, a step
/// halved until the largest residual falls, damped as J + mu I where J is singular); the
/// normal's dependence on the neighbouring heights enters the Jacobian through central
/// differences. The other sites rest on the support with radius 0. Returns the iterations.
int solve_sheet(const SurfacePair& pair, Sheet& sheet);

}  // namespace palpa::anatomy
