#pragma once
// Tessellation for display: a contour surface evaluated on a (u, v) grid whose lines
// follow the knots and whose density per span comes from an error tolerance through
// rigorous bounds on the second derivatives (tessellation_grid.hpp), output as plain
// arrays that ui/ turns into VTK data. core/ knows nothing of VTK: positions, normals and triangle indices are
// plain vectors, and only bodies that changed are tessellated again (BodyMeshes).
#include <cstdint>
#include <vector>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/render/tessellation_grid.hpp"
#include "palpa/spline/bspline_surface.hpp"

namespace palpa::render {

/// A triangulated grid of surface points. Vertex (i, j), i = 0..rows-1 along u and
/// j = 0..cols-1 along v, has index i * cols + j and lies at S(us[i], vs[j]); the grid
/// lines run from the first to the last knot ([0, 1]^2 for fitted bodies).
/// Re-tessellating into the same Mesh reuses its storage: once the vectors have the
/// capacity for a grid, tessellating a grid of that size or smaller allocates nothing.
struct Mesh {
  std::vector<float> positions;  ///< xyz per vertex (m)
  std::vector<float> normals;    ///< unit, per vertex, pointing to the outward side
  std::vector<std::uint32_t> triangles;  ///< 3 per triangle, counter-clockwise seen from the normal side
  std::vector<double> us, vs;            ///< parameters of the grid lines (rows, cols entries)
  int rows = 0, cols = 0;                ///< vertex grid (segments + 1 per direction)
  /// The a-priori bound on the distance between a triangle and the surface over the same
  /// parameters for the chosen grid: <= the tolerance unless max_segments was reached.
  double error_bound = 0.0;
  /// Which side the normals and the winding face: false +N (Su x Sv), true -N.
  bool outward_is_minus_normal = false;
  /// Internal: the grid choice, basis tables and one row curve, kept here so that
  /// re-tessellating allocates nothing.
  GridScratch grid;
  std::vector<double> scratch;
  std::vector<int> scratch_spans;

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
};

/// Tessellates the xyz channels of s into out: positions and unit normals
/// normalize(Su x Sv), negated when outward_is_minus_normal (the bottom contour's
/// outside is its -N side), and triangles wound counter-clockwise seen from the normal
/// side. Where Su x Sv vanishes (a pole row or column) the normal is the limit direction
/// from the interior, else the average of the neighbouring vertices' normals; never NaN.
/// The grid is choose_grid's for the tolerance less the float rounding of the positions.
/// Triangle indices are rebuilt only when the grid size or the side changed.
/// Throws std::invalid_argument for invalid options or s.dim() < 3.
void tessellate(const spline::BSplineSurface& s, const TessellationOptions& o, bool outward_is_minus_normal,
                Mesh& out);

/// Largest distance between the mesh and the surface over the same parameters: each
/// triangle sampled at the barycentric points (a, b, c) / n, a + b + c = n
/// (n = samples_per_edge), the linearly interpolated position against S at the linearly
/// interpolated (u, v). This is the deviation cell_error_bound controls. For tests and
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
