#pragma once
// Line plots for benchmark figures (time vs size, error vs time, ...), rendered with
// OpenCV: no Qt, no VTK, so figures can be made on a headless server.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace palpa::plot {

enum class Scale { Linear, Log10 };
enum class Marker { None, Circle, Square, Triangle, Cross };

/// One curve. x and y are paired by index (the shorter length wins). Text is drawn with
/// OpenCV's Hershey font, which has ASCII glyphs only ("us", not "µs").
struct Series {
  std::string label;  ///< shown in the legend; series with an empty label are left out of it
  std::vector<double> x, y;
  Marker marker = Marker::Circle;
  bool line = true;  ///< join consecutive points; a skipped point breaks the line
};

struct Axis {
  std::string label;
  Scale scale = Scale::Linear;
  std::optional<double> min, max;  ///< fixed limits; unset ones come from the data
};

struct LinePlot {
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  int width = 1000, height = 650;  ///< pixels; at least 200 x 150
};

/// The data limits of one axis after defaults are applied.
struct AxisRange {
  Scale scale = Scale::Linear;
  double min = 0.0, max = 1.0;
  /// Where v lies between min (0) and max (1), in log10 on a log axis; nullopt if v is
  /// not finite, or <= 0 on a log axis.
  std::optional<double> fraction(double v) const;
};

/// Where the data goes in the image: the plot area (the axes box) and the two ranges.
struct Frame {
  cv::Rect area;  ///< the box is drawn from area.tl() to area.br(); y grows downwards
  AxisRange x, y;
  /// The pixel (sub-pixel precise) of a data point, or nullopt if it cannot be plotted.
  /// Points outside the ranges map outside the area.
  std::optional<cv::Point2d> to_pixel(double x_value, double y_value) const;
};

/// The layout render() uses. Throws std::invalid_argument for a size below 200 x 150 or
/// axis limits that are not finite, not positive on a log axis, or min >= max.
Frame frame_of(const LinePlot& plot);

/// The colour (BGR) of series i: Okabe-Ito, a colour-blind-safe palette, repeating after 8.
cv::Scalar series_colour(std::size_t i);

/// Renders to an 8-bit BGR image: white background, axes with ticks and tick labels
/// (decades on log axes, written "1e-6"), grid lines, title, axis labels, one colour per
/// series, markers and lines, and a legend box in the emptiest corner of the plot area.
/// Points that are non-finite, or <= 0 on a log axis, are skipped. Axis ranges default
/// to the data range with a 5% margin (whole decades on log axes). An empty plot renders
/// axes only. Throws what frame_of throws.
cv::Mat render(const LinePlot& plot);

/// Writes render(plot) as a PNG (whatever the extension); throws std::runtime_error
/// naming the path if it cannot.
void save_png(const LinePlot& plot, const std::filesystem::path& path);

}  // namespace palpa::plot
