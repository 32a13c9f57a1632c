#pragma once
// Tessellation for display: a contour surface evaluated on a uniform (u, v) grid whose
// density comes from an error tolerance through rigorous bounds on the second
// derivatives (Filip, Magedson and Markot 1986), output as plain arrays that ui/ turns
// into VTK data. core/ knows nothing of VTK: positions, normals and triangle indices are
// plain vectors, and only bodies that changed are tessellated again (BodyMeshes).
#include <cstdint>
#include <vector>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/spline/bspline_surface.hpp"

namespace palpa::render {

/// A triangulated grid of surface points. Vertex (i, j), i = 0..rows-1 along u and
/// j = 0..cols-1 along v, has index i * cols + j and lies at
///   S(u0 + i (u1 - u0) / (rows - 1), v0 + j (v1 - v0) / (cols - 1))
/// where [u0, u1] x [v0, v1] is the surface's knot range ([0, 1]^2 for fitted bodies).
/// Re-tessellating into the same Mesh reuses its storage: once the vectors have the
/// capacity for a grid, tessellating a grid of that size or smaller allocates nothing.
struct Mesh {
  std::vector<float> positions;  ///< xyz per vertex (m)
  std::vector<float> normals;    ///< unit, per vertex, pointing to the outward side
  std::vector<std::uint32_t> triangles;  ///< 3 per triangle, counter-clockwise seen from the normal side
  int rows = 0, cols = 0;                ///< vertex grid (segments + 1 per direction)
  /// The a-priori bound on the distance between a triangle and the surface over the same
  /// parameters for the chosen grid: <= the tolerance unless max_segments was reached.
  double error_bound = 0.0;
  /// Which side the normals and the winding face: false +N (Su x Sv), true -N.
  bool outward_is_minus_normal = false;
  /// Internal: basis tables and one row curve, kept here so that re-tessellating allocates nothing.
  std::vector<double> scratch;
  std::vector<int> scratch_spans;

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
};

/// Upper bounds of |Suu|, |Suv| and |Svv| (Euclidean norm of the xyz channels) over the
/// whole parameter domain.
struct DerivativeBounds {
  double suu = 0, suv = 0, svv = 0;
};

/// Bounds the second derivatives of the first three channels of s by the largest norm
/// of the control points of its derivative surfaces (The NURBS Book eq. 3.17 and
/// A3.7, applied per direction): a derivative surface is a B-spline whose value is a
/// convex combination of its control points, so the bound holds everywhere. It is exact
/// when the derivative is constant (a quadratic in that direction). A direction of
/// degree 1 has zero second derivative inside its spans; if it also has interior knots
/// the surface is only C0 there and no second-derivative bound controls the error: such
/// surfaces are not made by the fitter (degree 1 only with 2 points, one span).
/// Allocation-free. Requires s.dim() >= 3.
DerivativeBounds second_derivative_bounds(const spline::BSplineSurface& s);

struct TessellationOptions {
  /// Largest distance (m, object space) between a triangle and the surface over the same
  /// parameters. For a screen-space tolerance use object_tolerance_from_screen.
  double tolerance = 2e-4;
  int min_segments = 2;    ///< per direction, >= 1
  int max_segments = 512;  ///< per direction, >= min_segments

  bool operator==(const TessellationOptions&) const = default;
};

/// The object-space tolerance that keeps the error below `pixels` on screen, where
/// pixels_per_metre is the projected size of one metre at the body (the UI passes it:
/// for a perspective camera viewport_height_px / (2 d tan(fov_y / 2)) at the distance d
/// of the body's nearest point, for a parallel projection viewport_height_px / (2 *
/// parallel_scale)). Throws std::invalid_argument unless both are positive and finite.
double object_tolerance_from_screen(double pixels, double pixels_per_metre);

/// Segments per direction for a surface with the given bounds over parameter ranges
/// range_u x range_v, and the bound they achieve.
struct Segments {
  int u = 0, v = 0;
  double bound = 0.0;
};

/// The error bound of a uniform grid of nu x nv segments: a linear interpolant over
/// each half of a cell of steps hu = range_u / nu, hv = range_v / nv deviates from the
/// surface by at most (1/8)(hu^2 suu + 2 hu hv suv + hv^2 svv) (Filip, Magedson and
/// Markot 1986).
double grid_error_bound(const DerivativeBounds& b, double range_u, double range_v, int nu, int nv);

/// The grid with the fewest triangles whose grid_error_bound is within o.tolerance,
/// both counts in [min_segments, max_segments] (ties: the smaller bound). Fewest
/// triangles balances the directions: in the continuous limit hu^2 suu = hv^2 svv.
/// When no grid within max_segments meets the tolerance: max_segments in both
/// directions (and the bound it achieves). Throws std::invalid_argument for invalid options.
Segments choose_segments(const DerivativeBounds& b, const TessellationOptions& o, double range_u, double range_v);

/// Tessellates the xyz channels of s into out: positions and unit normals
/// normalize(Su x Sv), negated when outward_is_minus_normal (the bottom contour's
/// outside is its -N side), and triangles wound counter-clockwise seen from the normal
/// side. Where Su x Sv vanishes (a pole row or column) the normal is the limit direction
/// from the interior, else the average of the neighbouring vertices' normals; never NaN.
/// Triangle indices are rebuilt only when the grid size or the side changed.
/// Throws std::invalid_argument for invalid options or s.dim() < 3.
void tessellate(const spline::BSplineSurface& s, const TessellationOptions& o, bool outward_is_minus_normal,
                Mesh& out);

/// Largest distance between the mesh and the surface over the same parameters: each
/// triangle sampled at the barycentric points (a, b, c) / n, a + b + c = n
/// (n = samples_per_edge), the linearly interpolated position against S at the linearly
/// interpolated (u, v). This is the deviation grid_error_bound controls. For tests and
/// benchmarks (not real-time: it evaluates S at every sample).
double max_parametric_deviation(const Mesh& mesh, const spline::BSplineSurface& s, int samples_per_edge = 4);

/// The display meshes of one deformed body: top (outward +N) and bottom (outward -N).
class BodyMeshes {
 public:
  /// Re-tessellates top and bottom only if body.version() changed since the last call
  /// (or the options did, or this is another body than last time); returns true if it did.
  /// Allocation-free once the meshes have the capacity for the grids needed.
  bool update(const deform::DeformedBody& body, const TessellationOptions& o);
  const Mesh& top() const { return top_; }
  const Mesh& bottom() const { return bottom_; }

 private:
  Mesh top_, bottom_;
  const deform::DeformedBody* body_ = nullptr;
  std::uint64_t version_ = 0;
  TessellationOptions options_{};
  bool valid_ = false;
};

}  // namespace palpa::render
