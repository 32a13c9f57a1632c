#pragma once
// The live coverage drawn on the body (docs/user-guide.md, "Coverage overlay"): a dot on
// the skin over every cell of the exam region, coloured by the deepest pressure reached
// there so far: untouched (orange), touched at light or medium pressure only (blue),
// reached at deep pressure (green). The cells and levels are live::LiveCoverage's, the
// score's own grid.
#include <array>
#include <cstdint>
#include <vector>

#include <vtkSmartPointer.h>

#include "palpa/live/live_coverage.hpp"

class vtkActor;
class vtkPolyData;
class vtkRenderer;
class vtkUnsignedCharArray;

namespace palpa::ui {

class CoverageOverlay {
 public:
  /// The dots of `coverage`'s exam region, added to `renderer`, lifted off the skin on the
  /// side that faces `eye` (m; the default camera's position).
  CoverageOverlay(const live::LiveCoverage& coverage, vtkRenderer* renderer, const Vec3& eye);
  ~CoverageOverlay();
  CoverageOverlay(const CoverageOverlay&) = delete;
  CoverageOverlay& operator=(const CoverageOverlay&) = delete;

  /// Colours the dots by the levels now; true when anything changed (a frame is needed).
  bool sync();
  /// Thins the dots for the camera now, when it moved: per body every s-th row and column
  /// of the grid, s the least that keeps the dots shown kMinSpacing pixels apart on screen;
  /// a dot shown stands for its s x s block and takes its least level (a gap stays orange).
  /// True when the dots shown changed. (Under a software renderer drawing 70 000 dots of 35
  /// bodies cost more than the bodies.)
  bool fit_to_view();
  static constexpr double kMinSpacing = 4.0;  ///< px between dots shown (they are 3 px wide)
  /// Where the dots shown are (m).
  std::vector<Vec3> shown_dots() const;
  void set_visible(bool visible);
  bool visible() const;

  /// The colour of each level (0 untouched, 1 light, 2 medium, 3 deep), RGB 0..255.
  static constexpr std::array<std::array<std::uint8_t, 3>, 4> kColours = {{
      {{240, 140, 30}},   // untouched: orange
      {{90, 170, 250}},   // light
      {{90, 170, 250}},   // medium: the same blue, "touched, not deep"
      {{60, 200, 90}},    // deep: green
  }};

 private:
  const live::LiveCoverage& coverage_;
  vtkRenderer* renderer_;
  vtkSmartPointer<vtkActor> actor_;
  vtkSmartPointer<vtkUnsignedCharArray> colours_;
  std::vector<std::pair<std::size_t, std::size_t>> cells_;  ///< (body, cell) of each dot
  std::vector<std::size_t> shown_;  ///< the dots drawn (every stride-th row and column): sync() colours only these
  std::uint64_t drawn_version_ = ~std::uint64_t{0};
  vtkSmartPointer<vtkPolyData> dots_;
  std::vector<int> stride_;  ///< per body: every stride-th row and column shown
  std::array<double, 12> camera_view_{};  ///< the camera and view size the dots were thinned for
  std::uint8_t block_level(std::size_t body, std::size_t cell) const;
};

/// The skin normal of every cell of one body's grid (unit, from its neighbours' centres),
/// turned so that their area-weighted mean points the way of `outward` (the grid's own
/// orientation depends on how the body's (u, v) run).
std::vector<Vec3> cell_normals(const live::LiveCoverage& coverage, std::size_t body, const Vec3& outward);

/// Where the exam region is and which way it faces: its area-weighted centroid, its mean
/// skin normal (unit, pointing away from the bodies' middle) and the cells' centres.
struct RegionFacing {
  Vec3 centroid = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  std::vector<Vec3> points;  ///< centres of the region's cells (area > 0)
  double area = 0.0;         ///< m^2
};
RegionFacing region_facing(const live::LiveCoverage& coverage, const Vec3& bodies_centre);

}  // namespace palpa::ui
