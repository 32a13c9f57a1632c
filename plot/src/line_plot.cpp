#include "palpa/plot/line_plot.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace palpa::plot {
namespace {

constexpr int kMinWidth = 200;
constexpr int kMinHeight = 150;
constexpr int kFontFace = cv::FONT_HERSHEY_SIMPLEX;
// OpenCV draws at sub-pixel positions when coordinates are fixed-point with this many
// fractional bits; without it lines and markers snap to whole pixels and look jagged.
constexpr int kShift = 4;
constexpr double kOne = 1 << kShift;

const cv::Scalar kInk{40, 40, 40};
const cv::Scalar kGrid{222, 222, 222};
const cv::Scalar kMinorGrid{243, 243, 243};
const cv::Scalar kLegendEdge{190, 190, 190};
const cv::Scalar kWhite{255, 255, 255};

struct Font {
  double scale;
  int thickness;
};

/// Sizes in pixels for the default 1000 x 650 image; larger images scale them up so a
/// figure made for print keeps its proportions. Small images shrink them less, or the
/// Hershey font becomes unreadable.
struct Style {
  double s;
  Font title, label, tick, legend;
  double pad, tick_length, marker_radius;
  int line_thickness;

  explicit Style(const LinePlot& plot)
      : s(std::clamp(std::min(plot.width / 1000.0, plot.height / 650.0), 0.7, 4.0)),
        title{0.8 * s, thick(2)},
        label{0.6 * s, thick(1)},
        tick{0.5 * s, thick(1)},
        legend{0.5 * s, thick(1)},
        pad(12 * s),
        tick_length(6 * s),
        marker_radius(4.5 * s),
        line_thickness(thick(2)) {}

  int thick(double t) const { return std::max(1, cvRound(t * s)); }
};

struct TextBox {
  int width, height, baseline;  // height is above the baseline, baseline below it
};

TextBox measure(const std::string& text, Font f) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFontFace, f.scale, f.thickness, &baseline);
  return {size.width, size.height, baseline};
}

/// Draws text so that the point `at` falls at (align_x, align_y) of its box: 0 = left or
/// top, 0.5 = centre, 1 = right or bottom. The box spans the capitals, not descenders.
void put_text(cv::Mat& image, const std::string& text, cv::Point2d at, Font f, double align_x, double align_y) {
  const TextBox box = measure(text, f);
  const cv::Point origin(cvRound(at.x - align_x * box.width), cvRound(at.y + (1.0 - align_y) * box.height));
  cv::putText(image, text, origin, kFontFace, f.scale, kInk, f.thickness, cv::LINE_AA);
}

cv::Point fixed(cv::Point2d p) { return {cvRound(p.x * kOne), cvRound(p.y * kOne)}; }

bool usable(double v, Scale scale) { return std::isfinite(v) && (scale == Scale::Linear || v > 0.0); }

// ---- axis ranges ------------------------------------------------------------------

void check_limits(const Axis& axis, const char* name) {
  const auto bad = [&](const std::string& why) {
    throw std::invalid_argument(std::string("palpa::plot: ") + name + " axis: " + why);
  };
  for (const auto& limit : {axis.min, axis.max}) {
    if (limit && !std::isfinite(*limit)) bad("limit is not finite");
    if (limit && axis.scale == Scale::Log10 && *limit <= 0.0) bad("limit must be > 0 on a log axis");
  }
  if (axis.min && axis.max && !(*axis.min < *axis.max)) bad("min must be below max");
}

/// Works in "axis space" (the value, or its log10) so both scales share one rule.
AxisRange range_of(const Axis& axis, std::optional<double> data_min, std::optional<double> data_max) {
  const bool log = axis.scale == Scale::Log10;
  const auto to_axis = [&](double v) { return log ? std::log10(v) : v; };
  double lo = 0.0;
  double hi = 1.0;
  if (data_min) {
    lo = to_axis(*data_min);
    hi = to_axis(*data_max);
    if (log) {
      lo = std::floor(lo);
      hi = std::ceil(hi);
      if (lo == hi) {  // all data on one decade line: centre it
        lo -= 1.0;
        hi += 1.0;
      }
    } else if (lo == hi) {
      const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
      lo -= pad;
      hi += pad;
    } else {
      const double pad = 0.05 * hi - 0.05 * lo;  // written so it cannot overflow
      lo -= pad;
      hi += pad;
    }
    if (!std::isfinite(lo) || !std::isfinite(hi)) {  // data near the double limits
      lo = to_axis(*data_min);
      hi = to_axis(*data_max);
    }
  }
  // One fixed limit with the data on the wrong side of it: keep the default span.
  const double span = hi - lo;
  if (axis.min) lo = to_axis(*axis.min);
  if (axis.max) hi = to_axis(*axis.max);
  if (!(lo < hi)) {
    if (axis.min) {
      hi = lo + span;
    } else {
      lo = hi - span;
    }
  }
  // Fixed limits as given; computed ones kept finite (and > 0 on a log axis) even for
  // data at the ends of the double range, so the mapping and ticks stay finite.
  const auto from_axis = [&](double a) { return log ? std::pow(10.0, a) : a; };
  const double lowest = log ? std::numeric_limits<double>::denorm_min() : std::numeric_limits<double>::lowest();
  const double highest = std::numeric_limits<double>::max();
  const double min = axis.min ? *axis.min : std::clamp(from_axis(lo), lowest, highest);
  const double max = axis.max ? *axis.max : std::clamp(from_axis(hi), lowest, highest);
  return {axis.scale, min < max ? min : std::nextafter(max, lowest), max};
}

// ---- ticks ------------------------------------------------------------------------

struct Tick {
  double value;
  std::string label;  // empty for a minor tick
};

/// 1, 2 or 5 times a power of ten, giving about `count` steps over `span`.
double nice_step(double span, double count) {
  const double raw = span / count;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / decade;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * decade;
}

/// "2.5e-06" -> "2.5e-6", "1e+03" -> "1e3".
std::string compact_scientific(const std::string& text) {
  const auto e = text.find('e');
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  if (exponent.empty()) return text.substr(0, e);
  return text.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

/// A tick label with just enough digits to tell ticks `step` apart ("0.5", "2.8e-5").
std::string format_tick(double v, double step) {
  if (std::abs(v) < 1e-6 * step) v = 0.0;  // no "-0.0" or "1e-17" at zero
  const int step_exponent = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  const bool scientific = step >= 1e6 || step < 1e-4 || std::abs(v) >= 1e6;
  std::array<char, 64> buffer{};
  if (scientific && v == 0.0) return "0";
  if (scientific) {
    const int v_exponent = static_cast<int>(std::floor(std::log10(std::abs(v))));
    const int digits = std::clamp(v_exponent - step_exponent, 0, 15);
    const auto end =
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::scientific, digits).ptr;
    return compact_scientific(std::string(buffer.data(), end));
  }
  const int decimals = std::clamp(-step_exponent, 0, 15);
  const auto end =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::fixed, decimals).ptr;
  return std::string(buffer.data(), end);
}

std::vector<Tick> linear_ticks(double lo, double hi, double count) {
  const double step = nice_step(hi - lo, count);
  std::vector<Tick> ticks;
  if (!std::isfinite(step) || step <= 0.0) return ticks;  // a span beyond the double range
  // Integer multiples of the step (no accumulated round-off); the cap guards a span
  // that is tiny next to its values, where k + 1 == k in floating point.
  const double last = std::floor(hi / step + 1e-9);
  for (double k = std::ceil(lo / step - 1e-9); k <= last && ticks.size() < 100; k += 1.0) {
    if (std::isfinite(k * step)) ticks.push_back({k * step, format_tick(k * step, step)});
  }
  return ticks;
}

std::vector<Tick> log_ticks(const AxisRange& r, double length_px, double spacing_px) {
  const double lo = std::log10(r.min);
  const double hi = std::log10(r.max);
  const int first = static_cast<int>(std::ceil(lo - 1e-9));
  const int last = static_cast<int>(std::floor(hi + 1e-9));
  if (last - first < 1) {  // less than two decade lines: nice values, placed logarithmically
    return linear_ticks(r.min, r.max, std::max(2.0, length_px / spacing_px));
  }
  // Label every decade, or every 2nd, 3rd, 5th, ... when they would crowd (doubles
  // span about 630 decades, so the list is long enough).
  const double crowding = (last - first + 1) / std::max(2.0, length_px / spacing_px);
  int every = 1;
  for (const int next : {2, 3, 5, 10, 20, 50, 100, 200, 500}) {
    if (crowding > every) every = next;
  }
  const double px_per_decade = length_px / (hi - lo);
  std::vector<Tick> ticks;
  for (int e = static_cast<int>(std::floor(lo)); e <= static_cast<int>(std::ceil(hi)); ++e) {
    const double decade = std::pow(10.0, e);
    if (e >= first && e <= last) {
      ticks.push_back({decade, e % every == 0 ? fmt::format("1e{}", e) : std::string()});
    }
    if (every == 1 && px_per_decade >= 40.0) {
      for (int m = 2; m <= 9; ++m) {
        const double v = m * decade;
        if (v >= r.min && v <= r.max) ticks.push_back({v, {}});
      }
    }
  }
  return ticks;
}

std::vector<Tick> ticks_of(const AxisRange& r, double length_px, double spacing_px) {
  return r.scale == Scale::Log10 ? log_ticks(r, length_px, spacing_px)
                                 : linear_ticks(r.min, r.max, std::max(2.0, length_px / spacing_px));
}

// ---- layout -----------------------------------------------------------------------

struct Layout {
  Style style;
  Frame frame;
  std::vector<Tick> x_ticks, y_ticks;
};

int widest_label(const std::vector<Tick>& ticks, Font f) {
  int w = 0;
  for (const auto& t : ticks) w = std::max(w, measure(t.label, f).width);
  return w;
}

Layout layout_of(const LinePlot& plot) {
  if (plot.width < kMinWidth || plot.height < kMinHeight) {
    throw std::invalid_argument(
        fmt::format("palpa::plot: image size {} x {} is below the minimum 200 x 150", plot.width, plot.height));
  }
  check_limits(plot.x, "x");
  check_limits(plot.y, "y");

  // Data limits over the points that will be drawn (usable on both axes).
  std::optional<double> x_min, x_max, y_min, y_max;
  for (const auto& series : plot.series) {
    for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
      const double x = series.x[i];
      const double y = series.y[i];
      if (!usable(x, plot.x.scale) || !usable(y, plot.y.scale)) continue;
      x_min = std::min(x_min.value_or(x), x);
      x_max = std::max(x_max.value_or(x), x);
      y_min = std::min(y_min.value_or(y), y);
      y_max = std::max(y_max.value_or(y), y);
    }
  }

  Layout l{Style(plot), {}, {}, {}};
  const Style& st = l.style;
  l.frame.x = range_of(plot.x, x_min, x_max);
  l.frame.y = range_of(plot.y, y_min, y_max);

  const TextBox title = measure("Ag", st.title);
  const TextBox label = measure("Ag", st.label);
  const TextBox tick = measure("0", st.tick);
  const double top = st.pad + (plot.title.empty() ? tick.height : title.height + title.baseline + st.pad);
  const double bottom = st.tick_length + 6 * st.s + tick.height + tick.baseline +
                        (plot.x.label.empty() ? 0.0 : 10 * st.s + label.height + label.baseline) + st.pad;
  const double area_height = plot.height - top - bottom;
  l.y_ticks = ticks_of(l.frame.y, area_height, 60 * st.s);

  // Margins are capped so that absurd tick labels (a span of 1e-15 around 1) cannot
  // squeeze the plot area away; such labels are cut at the image edge instead.
  const double left =
      std::min(0.4 * plot.width, st.pad + (plot.y.label.empty() ? 0.0 : label.height + label.baseline + 10 * st.s) +
                                     widest_label(l.y_ticks, st.tick) + 6 * st.s + st.tick_length);
  // The last x tick label is centred on the right edge: leave room for half of it.
  const double estimated_width = plot.width - left - 30 * st.s;
  l.x_ticks = ticks_of(l.frame.x, estimated_width, 100 * st.s);
  const double right = std::clamp(widest_label(l.x_ticks, st.tick) / 2.0 + st.pad / 2.0, 30 * st.s, 0.2 * plot.width);

  l.frame.area = cv::Rect(cv::Point(cvRound(left), cvRound(top)),
                          cv::Point(plot.width - cvRound(right), plot.height - cvRound(bottom)));
  return l;
}

// ---- drawing ----------------------------------------------------------------------

/// Liang-Barsky: clips the segment a-b to `box`; false if nothing of it is inside.
bool clip_segment(cv::Point2d& a, cv::Point2d& b, const cv::Rect2d& box) {
  const cv::Point2d d = b - a;
  double t0 = 0.0;
  double t1 = 1.0;
  const std::array<std::pair<double, double>, 4> edges{{
      {-d.x, a.x - box.x},
      {d.x, box.x + box.width - a.x},
      {-d.y, a.y - box.y},
      {d.y, box.y + box.height - a.y},
  }};
  for (const auto& [p, q] : edges) {
    if (p == 0.0) {
      if (q < 0.0) return false;
    } else if (p < 0.0) {
      t0 = std::max(t0, q / p);
    } else {
      t1 = std::min(t1, q / p);
    }
  }
  if (t0 > t1) return false;
  const cv::Point2d start = a;
  a = start + t0 * d;
  b = start + t1 * d;
  return true;
}

void draw_marker(cv::Mat& image, cv::Point2d c, Marker marker, const cv::Scalar& colour, const Style& st) {
  const double r = st.marker_radius;
  const auto polygon = [&](std::initializer_list<cv::Point2d> offsets) {
    std::vector<cv::Point> points;
    for (const auto& o : offsets) points.push_back(fixed(c + o));
    cv::fillConvexPoly(image, points, colour, cv::LINE_AA, kShift);
  };
  switch (marker) {
    case Marker::None:
      break;
    case Marker::Circle:
      cv::circle(image, fixed(c), cvRound(r * kOne), colour, cv::FILLED, cv::LINE_AA, kShift);
      break;
    case Marker::Square: {
      const double h = 0.85 * r;  // about the same ink as the circle
      polygon({{-h, -h}, {h, -h}, {h, h}, {-h, h}});
      break;
    }
    case Marker::Triangle: {
      const double h = 1.25 * r;  // vertices on a circle around the centroid
      polygon({{0.0, -h}, {0.866 * h, 0.5 * h}, {-0.866 * h, 0.5 * h}});
      break;
    }
    case Marker::Cross: {
      const double h = r;
      cv::line(image, fixed(c + cv::Point2d(-h, -h)), fixed(c + cv::Point2d(h, h)), colour, st.line_thickness,
               cv::LINE_AA, kShift);
      cv::line(image, fixed(c + cv::Point2d(-h, h)), fixed(c + cv::Point2d(h, -h)), colour, st.line_thickness,
               cv::LINE_AA, kShift);
      break;
    }
  }
}

void draw_grid(cv::Mat& image, const Layout& l) {
  const cv::Rect& a = l.frame.area;
  for (const auto& t : l.x_ticks) {
    const auto f = l.frame.x.fraction(t.value);
    if (!f) continue;
    const int px = cvRound(a.x + *f * a.width);
    cv::line(image, {px, a.y}, {px, a.y + a.height}, t.label.empty() ? kMinorGrid : kGrid, 1);
  }
  for (const auto& t : l.y_ticks) {
    const auto f = l.frame.y.fraction(t.value);
    if (!f) continue;
    const int py = cvRound(a.y + (1.0 - *f) * a.height);
    cv::line(image, {a.x, py}, {a.x + a.width, py}, t.label.empty() ? kMinorGrid : kGrid, 1);
  }
}

void draw_axes(cv::Mat& image, const Layout& l) {
  const cv::Rect& a = l.frame.area;
  const Style& st = l.style;
  cv::rectangle(image, a.tl(), a.br(), kInk, 1);
  for (const auto& t : l.x_ticks) {
    const auto f = l.frame.x.fraction(t.value);
    if (!f) continue;
    const int px = cvRound(a.x + *f * a.width);
    const double length = t.label.empty() ? st.tick_length / 2 : st.tick_length;
    cv::line(image, {px, a.y + a.height}, {px, a.y + a.height + cvRound(length)}, kInk, 1);
    const cv::Point2d label_top(px, a.y + a.height + st.tick_length + 6 * st.s);
    if (!t.label.empty()) put_text(image, t.label, label_top, st.tick, 0.5, 0.0);
  }
  for (const auto& t : l.y_ticks) {
    const auto f = l.frame.y.fraction(t.value);
    if (!f) continue;
    const int py = cvRound(a.y + (1.0 - *f) * a.height);
    const double length = t.label.empty() ? st.tick_length / 2 : st.tick_length;
    cv::line(image, {a.x - cvRound(length), py}, {a.x, py}, kInk, 1);
    const cv::Point2d label_right(a.x - st.tick_length - 6 * st.s, py);
    if (!t.label.empty()) put_text(image, t.label, label_right, st.tick, 1.0, 0.5);
  }
}

void draw_titles(cv::Mat& image, const LinePlot& plot, const Layout& l) {
  const cv::Rect& a = l.frame.area;
  const Style& st = l.style;
  const double centre_x = a.x + a.width / 2.0;
  if (!plot.title.empty()) put_text(image, plot.title, {centre_x, st.pad}, st.title, 0.5, 0.0);
  if (!plot.x.label.empty()) put_text(image, plot.x.label, {centre_x, plot.height - st.pad}, st.label, 0.5, 1.0);
  if (!plot.y.label.empty()) {
    // putText only draws horizontally: draw on a strip, turn it, and darken the image
    // with it (min) so anti-aliased edges blend with the white background.
    const TextBox box = measure(plot.y.label, st.label);
    cv::Mat strip(box.height + box.baseline + 2, box.width + 2, CV_8UC3, kWhite);
    cv::putText(strip, plot.y.label, {1, box.height + 1}, kFontFace, st.label.scale, kInk, st.label.thickness,
                cv::LINE_AA);
    cv::rotate(strip, strip, cv::ROTATE_90_COUNTERCLOCKWISE);
    const cv::Rect place(cvRound(st.pad), cvRound(a.y + a.height / 2.0 - strip.rows / 2.0), strip.cols, strip.rows);
    const cv::Rect visible = place & cv::Rect(0, 0, image.cols, image.rows);
    cv::Mat target = image(visible);
    cv::min(target, strip(cv::Rect(visible.tl() - place.tl(), visible.size())), target);
  }
}

/// Draws the series; marks the pixels they cover in `ink` (8-bit, image size), which
/// is where the legend should not go.
void draw_series(cv::Mat& image, cv::Mat& ink, const LinePlot& plot, const Layout& l) {
  const cv::Rect2d area(l.frame.area);
  const Style& st = l.style;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    const cv::Scalar colour = series_colour(s);
    std::vector<std::optional<cv::Point2d>> points;
    for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
      points.push_back(l.frame.to_pixel(series.x[i], series.y[i]));
    }
    for (std::size_t i = 1; series.line && i < points.size(); ++i) {
      if (!points[i - 1] || !points[i]) continue;
      cv::Point2d a = *points[i - 1];
      cv::Point2d b = *points[i];
      if (!clip_segment(a, b, area)) continue;
      cv::line(image, fixed(a), fixed(b), colour, st.line_thickness, cv::LINE_AA, kShift);
      cv::line(ink, fixed(a), fixed(b), 255, st.line_thickness, cv::LINE_8, kShift);
    }
    // Markers are drawn whole when their centre is inside, so points on a decade line at
    // the edge of a log axis are not cut in half.
    const cv::Rect2d reach(area.x - 0.5, area.y - 0.5, area.width + 1.0, area.height + 1.0);
    for (const auto& p : points) {
      if (!p || !reach.contains(*p)) continue;
      draw_marker(image, *p, series.marker, colour, st);
      cv::circle(ink, fixed(*p), cvRound(st.marker_radius * kOne), 255, cv::FILLED, cv::LINE_8, kShift);
    }
  }
}

void draw_legend(cv::Mat& image, const cv::Mat& ink, const LinePlot& plot, const Layout& l) {
  const Style& st = l.style;
  std::vector<std::size_t> entries;
  int text_width = 0;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    if (plot.series[s].label.empty()) continue;
    entries.push_back(s);
    text_width = std::max(text_width, measure(plot.series[s].label, st.legend).width);
  }
  if (entries.empty()) return;

  const TextBox text = measure("Ag", st.legend);
  const double row = text.height + text.baseline + 8 * st.s;
  const double sample = 32 * st.s;
  const double inner = 10 * st.s;
  const cv::Size2d size(inner + sample + inner + text_width + inner,
                        inner + row * static_cast<double>(entries.size()) + inner - 8 * st.s);

  // The corner hiding the least data (ties: top right, top left, bottom right, bottom left).
  const cv::Rect2d a(l.frame.area);
  const double gap = 10 * st.s;
  const std::array<cv::Point2d, 4> corners{{
      {a.br().x - gap - size.width, a.y + gap},
      {a.x + gap, a.y + gap},
      {a.br().x - gap - size.width, a.br().y - gap - size.height},
      {a.x + gap, a.br().y - gap - size.height},
  }};
  const cv::Rect image_rect(0, 0, image.cols, image.rows);
  const auto pixels_of = [&](const cv::Rect2d& r) {
    return cv::Rect(cv::Point(cvRound(r.x), cvRound(r.y)), cv::Point(cvRound(r.br().x), cvRound(r.br().y))) &
           image_rect;
  };
  cv::Rect2d box;
  int least = std::numeric_limits<int>::max();
  for (const auto& corner : corners) {
    const cv::Rect2d candidate(corner, size);
    const int hidden = cv::countNonZero(ink(pixels_of(candidate)));
    if (hidden < least) {
      least = hidden;
      box = candidate;
    }
  }

  // A slightly see-through box (like matplotlib's): data it must cover stays faintly visible.
  cv::Mat under = image(pixels_of(box));
  cv::addWeighted(under, 0.15, cv::Mat(under.size(), under.type(), kWhite), 0.85, 0.0, under);
  cv::rectangle(image, fixed(box.tl()), fixed(box.br()), kLegendEdge, 1, cv::LINE_AA, kShift);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Series& series = plot.series[entries[k]];
    const cv::Scalar colour = series_colour(entries[k]);
    const double y = box.y + inner + row * static_cast<double>(k) + text.height / 2.0;
    const cv::Point2d start(box.x + inner, y);
    const cv::Point2d end(start.x + sample, y);
    if (series.line) cv::line(image, fixed(start), fixed(end), colour, st.line_thickness, cv::LINE_AA, kShift);
    draw_marker(image, (start + end) / 2.0, series.marker, colour, st);
    put_text(image, series.label, {end.x + inner, y}, st.legend, 0.0, 0.5);
  }
}

}  // namespace

std::optional<double> AxisRange::fraction(double v) const {
  if (!usable(v, scale)) return std::nullopt;
  const double f = scale == Scale::Log10 ? (std::log10(v) - std::log10(min)) / (std::log10(max) - std::log10(min))
                                         : (v - min) / (max - min);
  if (!std::isfinite(f)) return std::nullopt;
  return f;
}

std::optional<cv::Point2d> Frame::to_pixel(double x_value, double y_value) const {
  const auto fx = x.fraction(x_value);
  const auto fy = y.fraction(y_value);
  if (!fx || !fy) return std::nullopt;
  const cv::Point2d p(area.x + *fx * area.width, area.y + (1.0 - *fy) * area.height);
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::nullopt;
  return p;
}

Frame frame_of(const LinePlot& plot) { return layout_of(plot).frame; }

cv::Scalar series_colour(std::size_t i) {
  // Okabe & Ito (2008) in RGB; yellow and black last: yellow is faint on white.
  static constexpr std::array<std::array<double, 3>, 8> kRgb{{
      {0, 114, 178},    // blue
      {230, 159, 0},    // orange
      {0, 158, 115},    // bluish green
      {213, 94, 0},     // vermillion
      {204, 121, 167},  // reddish purple
      {86, 180, 233},   // sky blue
      {0, 0, 0},        // black
      {240, 228, 66},   // yellow
  }};
  const auto& rgb = kRgb[i % kRgb.size()];
  return {rgb[2], rgb[1], rgb[0]};
}

cv::Mat render(const LinePlot& plot) {
  const Layout layout = layout_of(plot);
  cv::Mat image(plot.height, plot.width, CV_8UC3, kWhite);
  draw_grid(image, layout);
  // Axes before the data: a marker on the edge of the area (a decade line at the end of
  // a log axis) then stays whole instead of being crossed by the axis line.
  draw_axes(image, layout);
  cv::Mat ink(image.size(), CV_8UC1, cv::Scalar(0));
  draw_series(image, ink, plot, layout);
  draw_titles(image, plot, layout);
  draw_legend(image, ink, plot, layout);
  return image;
}

void save_png(const LinePlot& plot, const std::filesystem::path& path) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", render(plot), png)) throw std::runtime_error(path.string() + ": cannot encode the PNG");
  const auto folder = path.parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error)) {
    throw std::runtime_error(path.string() + ": cannot write: folder " + folder.string() + " does not exist");
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace palpa::plot
