#pragma once
// The top contour of one body sampled once on a (u, v) grid of cells (docs/scoring.md,
// "Coverage"): cell centres and areas for the coverage maps, and the grid's corner nodes
// for a cheap bilinear lookup of the top-contour point and the radius at a sample's
// (u, v), so scoring never evaluates a spline per haptic sample.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "palpa/mat/mat_body.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/vec3.hpp"

namespace palpa::score::detail {


/// The top-contour point over SK(u, v) and the local radius R(u, v), evaluated exactly.
struct TopPoint {
  Vec3 point = Vec3::Zero();
  double radius = 0.0;
};
TopPoint top_point(const mat::MatBody& body, double u, double v);

class ContourGrid {
 public:
  /// `parts`: the exam-region rectangles of this body; `whole`: the whole body is examined
  /// (no exam_region in the case). Cells are about `cell_size` m on the top contour,
  /// between kMinCells and kMaxCells per direction.
  ContourGrid(const mat::MatBody& body, const std::vector<io::RegionPart>& parts, bool whole, double cell_size = 0.002);

  static constexpr int kMinCells = 8;
  static constexpr int kMaxCells = 256;

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int cells() const { return rows_ * cols_; }
  /// Cell holding (u, v), row-major.
  int cell_of(double u, double v) const;
  /// Bilinear between the corner nodes: error ~ h^2/8 times the surface's second
  /// derivative, micrometres for 2 mm cells on tissue-sized curvature.
  void lookup(double u, double v, Vec3& top, double& radius) const;

  const std::vector<Vec3>& centers() const { return centers_; }
  const std::vector<double>& areas() const { return areas_; }  ///< 0 outside the exam region
  double region_area() const { return region_area_; }
  /// Largest half-diagonal of a cell (m): a point in a cell lies this close to its centre.
  double half_diagonal() const { return half_diagonal_; }
  /// Per cell: how far its corners lie from its centre (at least its half-diagonals), so a
  /// flood over the cells a pad touches goes only through cells that reach the pad, however
  /// large some other cell of the body is.
  const std::vector<double>& cell_reach() const { return cell_reach_; }
  /// The top-down view: a point projected on the plane across the body's mean top-contour
  /// normal (m), where the search pattern's directions and strip positions are measured.
  Eigen::Vector2d top_down(const Vec3& p) const { return {p.dot(e1_), p.dot(e2_)}; }

 private:
  int rows_ = 0, cols_ = 0;
  std::vector<Vec3> node_top_;     // (rows+1) x (cols+1)
  std::vector<double> node_radius_;
  std::vector<Vec3> centers_;
  std::vector<double> areas_;
  double region_area_ = 0.0;
  double half_diagonal_ = 0.0;
  std::vector<double> cell_reach_;
  Vec3 e1_ = Vec3::UnitX(), e2_ = Vec3::UnitY();
};

}  // namespace palpa::score::detail
