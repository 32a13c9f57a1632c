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
/// modulus (mat::column_modulus). Sites without tissue take the median of those with.
std::vector<double> column_moduli(const LabelVolume& volume, const LabelTable& table, const SurfacePair& pair,
                                  const FittedBody& fitted, double nu);

/// b of the body: that of the soft label with the most voxels (a body has one).
double dominant_stiffening(const LabelVolume& volume, const LabelTable& table);

}  // namespace palpa::anatomy
