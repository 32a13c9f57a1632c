#pragma once
// How fine a display tessellation must be: rigorous bounds on a surface's second
// derivatives (Filip, Magedson and Markot 1986) per knot-span patch, and the grid lines
// that keep every cell within an error tolerance. The grid follows the knots: each knot
// span is cut evenly into as many segments as the patches along it need, so a dent a
// fingertip wide (a few strongly curved spans of a refined display net) makes only the
// rows and columns through it fine, not the whole surface.
#include <vector>

#include "palpa/spline/bspline_surface.hpp"

namespace palpa::render {

/// Upper bounds of |Suu|, |Suv| and |Svv| (Euclidean norm of the xyz channels) over a
/// parameter region.
struct DerivativeBounds {
  double suu = 0, suv = 0, svv = 0;
};

struct TessellationOptions {
  /// Largest distance (m, object space) between a triangle and the surface over the same
  /// parameters. For a screen-space tolerance use object_tolerance_from_screen.
  double tolerance = 2e-4;
  int min_segments = 2;    ///< per direction, >= 1
  int max_segments = 512;  ///< per direction, >= min_segments
  /// Also consider the uniform n x n grid that meets the tolerance by the whole surface's
  /// bounds, and take it when it has fewer cells than the grid through the knots (a body
  /// far away on screen, whose tolerance is looser than a knot span's bend: level_of_detail.hpp).
  /// Only where the surface is C1 at every knot (a knot of multiplicity >= degree keeps
  /// the knot lines), which the bound needs.
  bool uniform_if_cheaper = false;

  bool operator==(const TessellationOptions&) const = default;
};

/// Working storage of patch_bounds and choose_grid, kept by the caller so that choosing
/// again for a surface of the same size allocates nothing.
struct GridScratch {
  std::vector<double> knots_u, knots_v;   ///< the distinct knots bounding the spans
  std::vector<int> span_u, span_v;        ///< each span's index in the knot vector
  std::vector<DerivativeBounds> patches;  ///< spans_u x spans_v, row-major
  std::vector<double> d2u, d2v, d11;      ///< norms of the derivative surfaces' control points
  std::vector<double> need_u, need_v;     ///< per span: the largest suu + suv (svv + suv) along it
  std::vector<int> seg_u, seg_v;          ///< segments per span
};

/// Bounds of the second derivatives of the first three channels of s on each of its
/// knot-span patches (g.patches, spans_u x spans_v row-major, the spans bounded by
/// g.knots_u and g.knots_v). A derivative surface is a B-spline whose value on a patch is
/// a convex combination of the control points supported there (The NURBS Book eq. 3.17
/// and A3.7, applied per direction), so the largest of their norms bounds it on that
/// patch; exact where the derivative is constant. A direction of degree 1 has zero second
/// derivative inside its spans. Requires s.dim() >= 3; allocation-free once g is sized.
void patch_bounds(const spline::BSplineSurface& s, GridScratch& g);

/// The bounds of patch_bounds over the whole parameter domain (allocates: for tests and tools).
DerivativeBounds second_derivative_bounds(const spline::BSplineSurface& s);

/// The object-space tolerance that keeps the error below `pixels` on screen, where
/// pixels_per_metre is the projected size of one metre at the body (the UI passes it:
/// for a perspective camera viewport_height_px / (2 d tan(fov_y / 2)) at the distance d
/// of the body's nearest point, for a parallel projection viewport_height_px / (2 *
/// parallel_scale)). Throws std::invalid_argument unless both are positive and finite.
double object_tolerance_from_screen(double pixels, double pixels_per_metre);

/// The error bound of a cell of hu x hv parameters where the bounds b hold: a linear
/// interpolant over each half of the cell deviates from the surface by at most
/// (1/8)(hu^2 suu + 2 hu hv suv + hv^2 svv) (Filip, Magedson and Markot 1986).
double cell_error_bound(const DerivativeBounds& b, double hu, double hv);

/// The error bound of a uniform grid of nu x nv segments over range_u x range_v with
/// bounds b holding everywhere.
double grid_error_bound(const DerivativeBounds& b, double range_u, double range_v, int nu, int nv);

/// Grid lines us, vs (increasing, from the first to the last knot, every distinct knot
/// among them, each span cut evenly) whose every cell is within o.tolerance by its patch's
/// bounds, with few lines: the cross term is split, 2 hu hv suv <= suv (hu^2 + hv^2),
/// and the tolerance shared between the directions in the proportion that gives the
/// fewest cells (one direction gets a share, tried in twentieths, the other what the
/// first's rounded-up counts leave). At least o.min_segments per direction (the widest segments split first).
/// With o.uniform_if_cheaper, the uniform grid within the tolerance instead when it has
/// fewer cells. When a direction would need more than o.max_segments: a uniform grid of max_segments
/// in both directions. Returns the largest cell bound (<= tolerance unless max_segments
/// was reached). Calls patch_bounds; allocation-free once g, us and vs are sized.
/// Throws std::invalid_argument for invalid options.
double choose_grid(const spline::BSplineSurface& s, const TessellationOptions& o, GridScratch& g,
                   std::vector<double>& us, std::vector<double>& vs);

}  // namespace palpa::render
