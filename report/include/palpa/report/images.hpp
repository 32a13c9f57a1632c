#pragma once
// The figures of a session report, drawn with OpenCV (8-bit BGR images):
//  - coverage heatmap: every body's exam map seen from its free side, looking down the
//    support's normal (the area-weighted mean normal of the top contours, as the score's
//    top-down view: docs/scoring.md), each cell filled between its neighbours' centres and
//    coloured by dwell time (viridis, with a colour bar); untouched cells of the exam region
//    grey, cells outside it (area 0) not drawn;
//  - pressure map: the same view coloured by the deepest pressure level reached;
//  - force over time: |F| and the indentation level (depth over local tissue thickness).
// Both maps reveal the tumours (circle of the tumour's radius, a dot at its centre: green
// found, red missed) and the marks (crosses), with a line from each mark to the tumour it hit.
#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"

namespace palpa::report {

class ForceTrace;

/// Where a scene point lands in a map image. The view looks down `normal` (out of the
/// bodies' free side) onto the plane across it: `right` to the right, `up` up (+y across the
/// normal, +z when the normal is along y: the trainee window's picture), one scale for both.
/// A body on a support whose normal is +z is seen as before: x to the right, y up.
struct TopView {
  using Axis = std::array<double, 3>;
  cv::Rect area;       ///< the drawing area in the image
  double x_min = 0.0;  ///< m along `right` at the area's left edge
  double y_max = 0.0;  ///< m along `up` at the area's top edge
  double scale = 1.0;  ///< pixels per m
  Axis right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0}, normal{0.0, 0.0, 1.0};  ///< unit, right = up x normal
  /// A point of the view's plane: x m along `right`, y m along `up`.
  cv::Point2d to_pixel(double x, double y) const {
    return {area.x + (x - x_min) * scale, area.y + (y_max - y) * scale};
  }
  /// A scene point (m).
  template <class T>
  cv::Point2d to_pixel(const std::array<T, 3>& p) const {
    return to_pixel(along(p, right), along(p, up));
  }
  /// How far a scene point lies along an axis (m).
  template <class T>
  static double along(const std::array<T, 3>& p, const Axis& axis) {
    return static_cast<double>(p[0]) * axis[0] + static_cast<double>(p[1]) * axis[1] +
           static_cast<double>(p[2]) * axis[2];
  }
};

/// The view both maps use: down the area-weighted mean normal of every map's top contour
/// (+z without one), the exam region's cells, the tumours and the marks fitted with a
/// margin into the map area of the image.
TopView map_view(const score::Score& score);

/// What the maps say of their view.
inline constexpr const char* kMapViewNote = "seen from the free side, along the support's normal";

/// Colours (BGR) the maps use, so tests and legends agree.
cv::Scalar found_colour();
cv::Scalar missed_colour();
cv::Scalar untouched_colour();
/// Pressure level 1 light, 2 medium, 3 deep (0: untouched_colour()).
cv::Scalar level_colour(int level);

cv::Mat coverage_heatmap(const score::Score& score);
cv::Mat pressure_map(const score::Score& score);

/// |F| (N) and the indentation level over time, two panels; each decimated to at most
/// about 2000 points by keeping the largest value of each run of samples (peaks survive).
/// The level is depth / (2 R) at the contact, R from the session's case; when that case
/// cannot be built the lower panel shows the depth in mm instead.
cv::Mat force_plot(const session::Session& session, const score::Score& score);
/// The same from a trace gathered while the samples streamed by (force_trace.hpp).
cv::Mat force_plot(const ForceTrace& trace, const score::Score& score);

/// PNG bytes of an image; throws std::runtime_error if OpenCV cannot encode it.
std::vector<std::uint8_t> png_bytes(const cv::Mat& image);

}  // namespace palpa::report
