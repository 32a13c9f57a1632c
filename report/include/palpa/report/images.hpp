#pragma once
// The figures of a session report, drawn with OpenCV (8-bit BGR images):
//  - coverage heatmap: a top-down (x, y) view of every body's exam map, each cell filled
//    between its neighbours' centres and coloured by dwell time (viridis, with a colour
//    bar); untouched cells of the exam region grey, cells outside it (area 0) not drawn;
//  - pressure map: the same view coloured by the deepest pressure level reached;
//  - force over time: |F| and the indentation level (depth over local tissue thickness).
// Both maps reveal the tumours (circle of the tumour's radius, a dot at its centre: green
// found, red missed) and the marks (crosses), with a line from each mark to the tumour it hit.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"

namespace palpa::report {

class ForceTrace;

/// Where scene (x, y) lands in a map image: x to the right, y up, one scale for both.
struct TopView {
  cv::Rect area;       ///< the drawing area in the image
  double x_min = 0.0;  ///< m at the area's left edge
  double y_max = 0.0;  ///< m at the area's top edge
  double scale = 1.0;  ///< pixels per m
  cv::Point2d to_pixel(double x, double y) const {
    return {area.x + (x - x_min) * scale, area.y + (y_max - y) * scale};
  }
};

/// The view both maps use: the exam region's cells, the tumours and the marks, fitted with
/// a margin into the map area of the image.
TopView map_view(const score::Score& score);

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
