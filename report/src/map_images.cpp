// Coverage and pressure maps seen from the bodies' free side (see images.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "palpa/report/encoding.hpp"
#include "palpa/report/images.hpp"

namespace palpa::report {
namespace {

constexpr int kWidth = 900, kHeight = 660;
const cv::Rect kMapArea{20, 50, 660, 560};
constexpr int kLegendX = 710;
constexpr int kShift = 4;  // sub-pixel bits for OpenCV drawing
constexpr double kOne = 1 << kShift;
const cv::Scalar kInk{40, 40, 40};
const cv::Scalar kWhite{255, 255, 255};
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

cv::Point fixed(const cv::Point2d& p) {
  return {static_cast<int>(std::lround(p.x * kOne)), static_cast<int>(std::lround(p.y * kOne))};
}

struct P2 {
  double x, y;
};

/// A cell centre in the view's plane (m along its right and up).
P2 cell_centre(const TopView& view, const score::BodyMap& map, int i, int j) {
  const auto& c = map.center[static_cast<std::size_t>(i * map.cols + j)];
  return {TopView::along(c, view.right), TopView::along(c, view.up)};
}

/// A cell centre on the grid extended by one cell on each side (linear extrapolation), so
/// border cells get corners too. Needs at least 2 x 2 cells.
P2 extended_centre(const TopView& view, const score::BodyMap& map, int i, int j) {
  const int ci = std::clamp(i, 0, map.rows - 1), cj = std::clamp(j, 0, map.cols - 1);
  const P2 c = cell_centre(view, map, ci, cj);
  P2 p = c;
  if (i != ci) {
    const P2 n = cell_centre(view, map, ci == 0 ? 1 : map.rows - 2, cj);
    p.x += c.x - n.x;
    p.y += c.y - n.y;
  }
  if (j != cj) {
    const P2 n = cell_centre(view, map, ci, cj == 0 ? 1 : map.cols - 2);
    p.x += c.x - n.x;
    p.y += c.y - n.y;
  }
  return p;
}

/// Corner between cells (i, j) and (i + di, j + dj), di, dj in {-1, +1}: the mean of the
/// four cell centres around it.
P2 corner(const TopView& view, const score::BodyMap& map, int i, int j, int di, int dj) {
  const P2 a = extended_centre(view, map, i, j), b = extended_centre(view, map, i + di, j);
  const P2 c = extended_centre(view, map, i, j + dj), d = extended_centre(view, map, i + di, j + dj);
  return {(a.x + b.x + c.x + d.x) / 4.0, (a.y + b.y + c.y + d.y) / 4.0};
}

bool map_is_valid(const score::BodyMap& m) {
  const auto n = static_cast<std::size_t>(std::max(0, m.rows) * std::max(0, m.cols));
  return m.rows > 0 && m.cols > 0 && m.area.size() == n && m.center.size() == n;
}

/// Fills every exam-region cell of every map with colour_of(map, index), lowest cells first
/// (along the view's normal) so that the top of a folded contour stays visible.
template <class ColourOf>
void draw_cells(cv::Mat& image, const TopView& view, const score::Score& score, ColourOf colour_of) {
  struct Cell {
    const score::BodyMap* map;
    int i, j;
    double height;
  };
  std::vector<Cell> cells;
  for (const auto& map : score.maps) {
    if (!map_is_valid(map)) continue;
    for (int i = 0; i < map.rows; ++i)
      for (int j = 0; j < map.cols; ++j) {
        const auto k = static_cast<std::size_t>(i * map.cols + j);
        if (map.area[k] > 0.0) cells.push_back({&map, i, j, TopView::along(map.center[k], view.normal)});
      }
  }
  std::stable_sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.height < b.height; });
  for (const auto& cell : cells) {
    const auto& map = *cell.map;
    const auto k = static_cast<std::size_t>(cell.i * map.cols + cell.j);
    const cv::Scalar colour = colour_of(map, k);
    if (map.rows >= 2 && map.cols >= 2) {
      std::array<cv::Point, 4> quad;
      const int d[4][2] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}};
      for (std::size_t q = 0; q < 4; ++q) {
        const P2 c = corner(view, map, cell.i, cell.j, d[q][0], d[q][1]);
        quad[q] = fixed(view.to_pixel(c.x, c.y));
      }
      cv::fillConvexPoly(image, quad.data(), 4, colour, cv::LINE_8, kShift);
    } else {  // a single row or column: a disc of the cell's area
      const P2 c = cell_centre(view, map, cell.i, cell.j);
      const double r = std::sqrt(map.area[k] / std::numbers::pi) * view.scale;
      cv::circle(image, fixed(view.to_pixel(c.x, c.y)), static_cast<int>(std::lround(std::max(1.0, r) * kOne)),
                 colour, cv::FILLED, cv::LINE_AA, kShift);
    }
  }
}

void put_text(cv::Mat& image, const std::string& text, cv::Point at, double size = 0.5, int thickness = 1) {
  cv::putText(image, text, at, kFont, size, kInk, thickness, cv::LINE_AA);
}

/// Printable ASCII only: Hershey fonts have no other glyphs.
std::string ascii(const std::string& text) {
  std::string out;
  for (const char c : text) out += (c >= 32 && c < 127) ? c : '?';
  return out;
}

void draw_truth(cv::Mat& image, const TopView& view, const score::Score& score) {
  const int n = static_cast<int>(score.tumours.size());
  for (const auto& mark : score.marks) {  // lines under everything else
    if (mark.tumour < 0 || mark.tumour >= n) continue;
    const auto& t = score.tumours[static_cast<std::size_t>(mark.tumour)];
    const auto a = fixed(view.to_pixel(mark.position));
    const auto b = fixed(view.to_pixel(t.center));
    cv::line(image, a, b, kWhite, 4, cv::LINE_AA, kShift);
    cv::line(image, a, b, kInk, 2, cv::LINE_AA, kShift);
  }
  for (const auto& t : score.tumours) {
    const auto c = fixed(view.to_pixel(t.center));
    const int r = static_cast<int>(std::lround(std::max(4.0, t.radius * view.scale) * kOne));
    const cv::Scalar colour = t.found ? found_colour() : missed_colour();
    cv::circle(image, c, r, kWhite, 5, cv::LINE_AA, kShift);
    cv::circle(image, c, r, colour, 3, cv::LINE_AA, kShift);
  }
  for (const auto& mark : score.marks) {
    const auto p = view.to_pixel(mark.position);
    for (const auto& [colour, width] : {std::pair{kWhite, 5}, std::pair{kInk, 2}}) {
      cv::line(image, fixed(p + cv::Point2d(-7, -7)), fixed(p + cv::Point2d(7, 7)), colour, width, cv::LINE_AA, kShift);
      cv::line(image, fixed(p + cv::Point2d(-7, 7)), fixed(p + cv::Point2d(7, -7)), colour, width, cv::LINE_AA, kShift);
    }
  }
  // Tumour centres last: a mark placed close to one must not hide where it really is.
  for (const auto& t : score.tumours) {
    const auto c = fixed(view.to_pixel(t.center));
    const cv::Scalar colour = t.found ? found_colour() : missed_colour();
    cv::circle(image, c, static_cast<int>(5 * kOne), kWhite, cv::FILLED, cv::LINE_AA, kShift);
    cv::circle(image, c, static_cast<int>(4 * kOne), colour, cv::FILLED, cv::LINE_8, kShift);
  }
}

/// "o found  o missed  x mark" and a scale bar under the map.
void draw_truth_legend(cv::Mat& image, const TopView& view) {
  const int y = kMapArea.y + kMapArea.height + 28;
  int x = kMapArea.x + 220;
  for (const auto& [colour, label] : {std::pair{found_colour(), "tumour found"}, std::pair{missed_colour(), "missed"}}) {
    cv::circle(image, {x, y - 5}, 7, colour, 3, cv::LINE_AA);
    put_text(image, label, {x + 14, y});
    x += 165;
  }
  cv::line(image, {x - 6, y - 11}, {x + 6, y + 1}, kInk, 2, cv::LINE_AA);
  cv::line(image, {x - 6, y + 1}, {x + 6, y - 11}, kInk, 2, cv::LINE_AA);
  put_text(image, "mark (line: the tumour it hit)", {x + 14, y});
  // Scale bar: the largest 1-2-5 length (m) up to 120 px.
  const double target = 120.0 / view.scale;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double length = decade;
  for (const double f : {2.0, 5.0})
    if (f * decade <= target) length = f * decade;
  const int x0 = kMapArea.x, x1 = kMapArea.x + static_cast<int>(std::lround(length * view.scale));
  cv::line(image, {x0, y}, {x1, y}, kInk, 2);
  cv::line(image, {x0, y - 5}, {x0, y + 5}, kInk, 2);
  cv::line(image, {x1, y - 5}, {x1, y + 5}, kInk, 2);
  put_text(image, number_text(std::round(length * 1e4) / 10.0) + " mm", {x1 + 8, y + 5});
}

cv::Mat blank(const std::string& title, const score::Score& score) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, kWhite);
  put_text(image, title, {kMapArea.x, 28}, 0.7, 2);
  put_text(image, kMapViewNote, {kMapArea.x, kMapArea.y - 6}, 0.45);
  if (std::none_of(score.maps.begin(), score.maps.end(), map_is_valid))
    put_text(image, "(no exam map in this score)", {kMapArea.x + 180, kMapArea.y + kMapArea.height / 2});
  return image;
}

cv::Scalar viridis(double fraction) {
  static const cv::Mat lut = [] {
    cv::Mat ramp(256, 1, CV_8UC1);
    for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i) = static_cast<std::uint8_t>(i);
    cv::Mat colours;
    cv::applyColorMap(ramp, colours, cv::COLORMAP_VIRIDIS);
    return colours;
  }();
  const int i = std::clamp(static_cast<int>(std::lround(fraction * 255.0)), 0, 255);
  const auto c = lut.at<cv::Vec3b>(i);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

using Axis = TopView::Axis;

Axis cross(const Axis& a, const Axis& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double length(const Axis& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/// The way out of the bodies' free side: the area-weighted mean normal of every map's top
/// contour, summed over the quads between its cell centres (the grid runs along the
/// skeleton's u and v, so u x v points out of the free side as the skeleton's normal does);
/// +z when no map has two rows and two columns of finite centres.
Axis free_side_normal(const score::Score& score) {
  Axis sum{0.0, 0.0, 0.0};
  for (const auto& map : score.maps) {
    if (!map_is_valid(map)) continue;
    const auto at = [&](int i, int j) {
      const auto& c = map.center[static_cast<std::size_t>(i * map.cols + j)];
      return Axis{c[0], c[1], c[2]};
    };
    for (int i = 0; i + 1 < map.rows; ++i)
      for (int j = 0; j + 1 < map.cols; ++j) {
        const Axis a = at(i, j), b = at(i + 1, j + 1), c = at(i, j + 1), d = at(i + 1, j);
        const Axis n = cross({b[0] - a[0], b[1] - a[1], b[2] - a[2]}, {c[0] - d[0], c[1] - d[1], c[2] - d[2]});
        if (std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]))
          for (std::size_t k = 0; k < 3; ++k) sum[k] += n[k];
      }
  }
  const double n = length(sum);
  if (!(n > 0.0)) return {0.0, 0.0, 1.0};
  return {sum[0] / n, sum[1] / n, sum[2] / n};
}

/// The picture's axes looking down `normal`: up is +y across it (+z when the normal is
/// along y), right = up x normal; the trainee window's default view frames the same way.
void set_axes(TopView& view, const Axis& normal) {
  const auto across = [&](const Axis& a) {
    const double d = a[0] * normal[0] + a[1] * normal[1] + a[2] * normal[2];
    return Axis{a[0] - d * normal[0], a[1] - d * normal[1], a[2] - d * normal[2]};
  };
  Axis up = across({0.0, 1.0, 0.0});
  if (length(up) < 0.2) up = across({0.0, 0.0, 1.0});
  const double n = length(up);
  view.normal = normal;
  view.up = {up[0] / n, up[1] / n, up[2] / n};
  view.right = cross(view.up, normal);
}

}  // namespace

cv::Scalar found_colour() { return {40, 170, 40}; }
cv::Scalar missed_colour() { return {30, 30, 225}; }
cv::Scalar untouched_colour() { return {200, 200, 200}; }
cv::Scalar level_colour(int level) {
  switch (level) {  // ColorBrewer Blues: light, medium, deep
    case 1: return {239, 219, 198};
    case 2: return {214, 174, 107};
    case 3: return {156, 81, 8};
    default: return untouched_colour();
  }
}

TopView map_view(const score::Score& score) {
  TopView view;
  set_axes(view, free_side_normal(score));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf;
  auto add = [&](const auto& point, double r) {
    const double x = TopView::along(point, view.right), y = TopView::along(point, view.up);
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x0 = std::min(x0, x - r);
    x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r);
    y1 = std::max(y1, y + r);
  };
  for (const auto& map : score.maps) {
    if (!map_is_valid(map)) continue;
    for (std::size_t k = 0; k < map.area.size(); ++k)
      if (map.area[k] > 0.0) add(map.center[k], std::sqrt(map.area[k]) / 2);
  }
  for (const auto& t : score.tumours) add(t.center, std::isfinite(t.radius) ? t.radius : 0.0);
  for (const auto& m : score.marks) add(m.position, 0.0);
  if (!(x0 <= x1)) x0 = y0 = -0.05, x1 = y1 = 0.05;
  // At least 1 cm across, and a 5 % margin.
  const double span = std::max({x1 - x0, y1 - y0, 0.01});
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const double wx = std::max(x1 - x0, span * 0.2) * 1.1, wy = std::max(y1 - y0, span * 0.2) * 1.1;
  view.scale = std::min(kMapArea.width / wx, kMapArea.height / wy);
  // Centre the drawing in the area.
  view.area = kMapArea;
  view.x_min = cx - kMapArea.width / view.scale / 2;
  view.y_max = cy + kMapArea.height / view.scale / 2;
  return view;
}

cv::Mat coverage_heatmap(const score::Score& score) {
  cv::Mat image = blank("Coverage: contact time per cell", score);
  const TopView view = map_view(score);
  float max_dwell = 0.0F;
  for (const auto& map : score.maps)
    for (std::size_t k = 0; k < map.dwell_s.size() && k < map.area.size(); ++k)
      if (map.area[k] > 0.0 && std::isfinite(map.dwell_s[k])) max_dwell = std::max(max_dwell, map.dwell_s[k]);
  draw_cells(image, view, score, [&](const score::BodyMap& map, std::size_t k) {
    const float dwell = k < map.dwell_s.size() ? map.dwell_s[k] : 0.0F;
    if (!(dwell > 0.0F) || max_dwell <= 0.0F) return untouched_colour();
    return viridis(static_cast<double>(dwell / max_dwell));
  });
  draw_truth(image, view, score);
  draw_truth_legend(image, view);
  // Colour bar: 0 at the bottom, the largest dwell at the top.
  const cv::Rect bar{kLegendX, 90, 28, 300};
  for (int r = 0; r < bar.height; ++r)
    cv::line(image, {bar.x, bar.y + r}, {bar.x + bar.width - 1, bar.y + r},
             viridis(1.0 - static_cast<double>(r) / (bar.height - 1)));
  cv::rectangle(image, bar, kInk, 1);
  put_text(image, "contact time", {kLegendX, 75});
  put_text(image, fmt::format("{:.3g} s", static_cast<double>(max_dwell)), {bar.x + bar.width + 8, bar.y + 6});
  put_text(image, "0 s", {bar.x + bar.width + 8, bar.y + bar.height});
  cv::rectangle(image, {kLegendX, 420, 28, 20}, untouched_colour(), cv::FILLED);
  cv::rectangle(image, {kLegendX, 420, 28, 20}, kInk, 1);
  put_text(image, "untouched", {kLegendX + 36, 435});
  return image;
}

cv::Mat pressure_map(const score::Score& score) {
  cv::Mat image = blank("Pressure: deepest level reached", score);
  const TopView view = map_view(score);
  draw_cells(image, view, score, [](const score::BodyMap& map, std::size_t k) {
    return level_colour(k < map.level.size() ? map.level[k] : 0);
  });
  draw_truth(image, view, score);
  draw_truth_legend(image, view);
  put_text(image, "deepest level", {kLegendX, 75});
  const char* names[4] = {"untouched", "light", "medium", "deep"};
  for (int level = 0; level < 4; ++level) {
    const cv::Rect box{kLegendX, 90 + 34 * level, 28, 22};
    cv::rectangle(image, box, level_colour(level), cv::FILLED);
    cv::rectangle(image, box, kInk, 1);
    put_text(image, names[level], {box.x + 36, box.y + 16});
  }
  put_text(image, ascii(fmt::format("depth/thickness: light < {:.2g},", score.thresholds.light_max)), {kLegendX, 250},
           0.4);
  put_text(image, ascii(fmt::format("deep >= {:.2g}", score.thresholds.deep_min)), {kLegendX, 268}, 0.4);
  return image;
}

std::vector<std::uint8_t> png_bytes(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  if (image.empty() || !cv::imencode(".png", image, bytes)) throw std::runtime_error("cannot encode a PNG image");
  return bytes;
}

}  // namespace palpa::report
