#pragma once
// A stiffness map: a 2-D grid of values in [0, 1] (for example a grayscale image, decoded
// by the UI; core never sees an image library) laid over a body's skeleton grid and
// turned into per-point stiffness between k_min and k_max (N/m), or into the tissue's
// Young's modulus between e_min and e_max (Pa) for a body given in kPa.
//
// Orientation: the map's rows run along the body's u (grid rows), its columns along v
// (grid columns). Skeleton point (i, j) samples the map at the normalized position
// (i / (rows - 1), j / (cols - 1)), row 0 / column 0 of the map at the body's first
// row / column.
#include <vector>

#include "palpa/mat/body_grid.hpp"

namespace palpa::author {

struct StiffnessMap {
  int rows = 0;
  int cols = 0;
  std::vector<double> values;  ///< rows*cols, row-major, each in [0, 1]
};

/// The map's value at normalized (u, v) in [0, 1]^2, averaged over a window of half-width
/// (half_u, half_v) (fractions of the map) shrunk symmetrically at the map's edges: a box
/// filter that removes detail finer than the skeleton grid (which the spline would turn
/// into overshoot) and returns a linear map's value exactly.
double sample_map(const StiffnessMap& map, double u, double v, double half_u, double half_v);

/// Per-point stiffness k_min + (k_max - k_min) * value for every skeleton point of `grid`,
/// each value averaged over the point's grid cell (sample_map with half a grid spacing).
/// Throws std::invalid_argument for an empty map, a size mismatch, values outside [0, 1]
/// or not finite, or 0 <= k_min <= k_max not holding.
std::vector<double> map_stiffness(const mat::BodyGrid& grid, const StiffnessMap& map, double k_min, double k_max);

/// Sets grid.stiffness from the map, then smooths it (each point averaged with its four
/// neighbours) until the body fits (the smooth-field check, docs/case-format.md "Smooth
/// material fields"), at most max_passes times. Returns the number of smoothing passes
/// used. Throws std::invalid_argument as map_stiffness, and mat::FitError when the body
/// does not fit even after max_passes (or for a reason other than the stiffness).
int apply_stiffness_map(mat::BodyGrid& grid, const StiffnessMap& map, double k_min, double k_max,
                        int max_passes = 50);

/// The same for a body given by its tissue's Young's modulus: grid.modulus from the map
/// (e_min..e_max, Pa), grid.stiffness derived from it over the local thickness as a case
/// file's is (mat::layer_stiffness_field), the modulus smoothed until the body fits.
/// Throws as apply_stiffness_map.
int apply_modulus_map(mat::BodyGrid& grid, const StiffnessMap& map, double e_min, double e_max, int max_passes = 50);

}  // namespace palpa::author
