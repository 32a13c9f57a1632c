#pragma once
// Internal to core/anatomy: the tissue's modulus at each skeleton point from the layers of
// labels its column crosses (docs/anatomy-import.md, "Tissue").
#include <vector>

#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/mat_fit.hpp"

namespace palpa::anatomy {

/// Pa per grid point (row-major) of `fitted`: the layered column from the support to the
/// free surface at each site, read from the volume along the frame's normal, as one
/// modulus (mat::column_modulus). Sites without tissue, or with under 3 voxels of it, take
/// the median of the others.
std::vector<double> column_moduli(const LabelVolume& volume, const LabelTable& table, const SurfacePair& pair,
                                  const FittedBody& fitted, double nu);

/// `modulus` (row-major, rows x cols) smoothed in place until the body's derived stiffness
/// no longer overshoots between its points (mat::MatBody::fit accepts it), each pass
/// replacing every point by the mean of its 3 x 3 neighbourhood: where tissue changes
/// abruptly between two points a spline through the stiffness dips below zero. Returns the
/// passes used; throws ImportError after 8.
int smooth_until_fits(mat::BodyGrid& body);

/// b of the body: that of the soft label with the most voxels (a body has one).
double dominant_stiffening(const LabelVolume& volume, const LabelTable& table);

}  // namespace palpa::anatomy
