#pragma once
// Internal to core/anatomy: a triangle mesh cut by lines along a frame's normal, and the
// checks a surface must pass before it is cut.
#include <vector>

#include "palpa/anatomy/height_field.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"

namespace palpa::anatomy {

/// The heights (along n) where the line through (s, t) crosses the mesh, found through a
/// grid of bins over the frame's plane holding the triangles each bin's square overlaps.
class ColumnCaster {
 public:
  ColumnCaster(const TriangleMesh& mesh, const Frame& frame, double bin);
  /// Sorted crossing heights, coincident ones (an edge shared by two triangles) once.
  void heights(double s, double t, std::vector<double>& out) const;

 private:
  std::vector<Vec3> local_;  // the points in the frame
  const TriangleMesh& mesh_;
  double s0_ = 0.0, t0_ = 0.0, bin_ = 1.0;
  int ns_ = 0, nt_ = 0;
  std::vector<std::vector<int>> bins_;
};

/// Where edges are shared by more than two triangles (non-manifold) and, when `closed`, by
/// fewer (an open border). Throws ImportError naming the first such edge in mm.
void check_edges(const TriangleMesh& mesh, bool closed, const std::string& source);

/// m: the median length of the mesh's edges (its resolution).
double median_edge(const TriangleMesh& mesh);

}  // namespace palpa::anatomy
