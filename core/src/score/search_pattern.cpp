#include "search_pattern.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "palpa/score/nearest_distance.hpp"

namespace palpa::score::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kResample = 0.002;             // m between resampled path points
// A step between two samples longer than this (a jump, or a hostile file alternating
// between the ends of a body) is one segment, not length / kResample of them: the work
// per sample stays bounded. At 1 kHz no hand moves this far in a tick.
constexpr double kLongestResampledStep = 0.004;  // m, two resampled steps (4 m/s at 1 kHz)
constexpr double kAxisTolerance = 20.0 * kPi / 180.0;  // a segment "along" the axis
constexpr double kLongRun = 0.020;              // m: a straight run this long is a strip
constexpr int kBins = 36;                       // 5 degree direction bins over [0, 180)
// The classes' bounds (docs/scoring.md, "Search pattern"): a complete search is efficient
// when most of its path runs in strips and little of it goes over covered ground again;
// an incomplete one is localized when it stayed in one compact part under half the region.
constexpr double kEfficientStripFraction = 0.6;
constexpr double kEfficientRevisitFraction = 0.3;
constexpr double kLocalizedCoverage = 0.5;

struct Segment {
  int body;
  int piece;
  double angle;  // axial direction in the body's top-down view, [0, pi)
  double length; // m over the top contour
  double x, y;   // midpoint in the top-down view (m)
  Vec3 mid;      // midpoint on the top contour (m)
};

double axial_difference(double a, double b) {
  double d = std::fmod(std::abs(a - b), kPi);
  return std::min(d, kPi - d);
}

// Resamples every piece of the path every kResample m of top-contour length and hands
// each segment between consecutive resampled points to `visit`, in path order. The
// segments are not kept: the passes over them resample again, so that memory stays that of
// the path (a hostile session can have two segments per sample).
template <class Visit>
void for_each_segment(const std::vector<PathPoint>& path, const std::vector<const ContourGrid*>& grids, Visit&& visit) {
  std::size_t begin = 0;
  while (begin < path.size()) {
    std::size_t end = begin + 1;
    while (end < path.size() && path[end].piece == path[begin].piece) ++end;
    const ContourGrid& g = *grids[static_cast<std::size_t>(path[begin].body)];
    auto view = [&](const Vec3& p) {
      const Eigen::Vector2d m = g.top_down(p);
      return std::array<double, 2>{m.x(), m.y()};
    };
    std::array<double, 2> last = view(path[begin].top);
    Vec3 last_top = path[begin].top;
    double since = 0.0;  // m of path since the last resampled point
    auto emit = [&](const Vec3& top, double length) {
      const std::array<double, 2> m = view(top);
      const double dx = m[0] - last[0];
      const double dy = m[1] - last[1];
      if (dx == 0.0 && dy == 0.0) return;
      double angle = std::atan2(dy, dx);
      if (angle < 0) angle += kPi;
      if (angle >= kPi) angle -= kPi;
      visit(Segment{path[begin].body, path[begin].piece, angle, length, 0.5 * (m[0] + last[0]),
                    0.5 * (m[1] + last[1]), 0.5 * (top + last_top)});
      last = m;
      last_top = top;
    };
    for (std::size_t k = begin + 1; k < end; ++k) {
      const PathPoint& a = path[k - 1];
      const PathPoint& b = path[k];
      const double seg = (b.top - a.top).norm();
      if (seg > kLongestResampledStep) {
        if (since > 0.0) emit(a.top, since);
        emit(b.top, seg);  // the same direction as its pieces would have: the view is linear
        since = 0.0;
        continue;
      }
      double done = 0.0;  // m of this segment already consumed
      while (since + (seg - done) >= kResample) {
        done += kResample - since;
        const double s = seg > 0 ? done / seg : 1.0;
        emit(a.top + s * (b.top - a.top), kResample);
        since = 0.0;
      }
      since += seg - done;
    }
    if (since > 0.0) emit(path[end - 1].top, since);
    begin = end;
  }
}

double median(std::vector<double> x) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 == 1 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

// Path length over the top contour and the share of it over ground covered before.
void measure_length(const std::vector<PathPoint>& path, SearchPattern& out) {
  double revisited = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    if (path[k].piece != path[k - 1].piece) continue;
    const double seg = (path[k].top - path[k - 1].top).norm();
    out.path_length_m += seg;
    if (path[k].revisit) revisited += seg;
  }
  if (out.path_length_m > 0.0) out.revisit_fraction = revisited / out.path_length_m;
}

// The dominant axis: the 45 degree window (+-20 degrees and a half bin) that holds the
// most path, refined by the axial mean of the segments in it (angles doubled). `total`
// gets the resampled path's length; no axis when it is 0.
std::optional<double> dominant_axis(const std::vector<PathPoint>& path, const std::vector<const ContourGrid*>& grids,
                                    double& total) {
  std::array<double, kBins> histogram{};
  total = 0.0;
  for_each_segment(path, grids, [&](const Segment& s) {
    histogram[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>(s.angle / kPi * kBins)))] += s.length;
    total += s.length;
  });
  if (total <= 0.0) return std::nullopt;
  int best = 0;
  double best_sum = -1.0;
  for (int b = 0; b < kBins; ++b) {
    double sum = 0.0;
    for (int d = -4; d <= 4; ++d) sum += histogram[static_cast<std::size_t>((b + d + kBins) % kBins)];
    if (sum > best_sum) {
      best_sum = sum;
      best = b;
    }
  }
  const double window_center = (best + 0.5) * kPi / kBins;
  double c2 = 0.0, s2 = 0.0;
  for_each_segment(path, grids, [&](const Segment& s) {
    if (axial_difference(s.angle, window_center) > kAxisTolerance + 0.5 * kPi / kBins) return;
    c2 += s.length * std::cos(2 * s.angle);
    s2 += s.length * std::sin(2 * s.angle);
  });
  return 0.5 * std::atan2(s2, c2);
}

// A straight run along the axis at least kLongRun long: its position across the axis in
// the top-down view, and its points on the top contour.
struct Run {
  double position;
  std::vector<Vec3> points;
};

// The runs of each body along `axis`; `along` gets the length of path along the axis.
std::vector<std::vector<Run>> runs_along(const std::vector<PathPoint>& path,
                                         const std::vector<const ContourGrid*>& grids, double axis, double& along) {
  std::vector<std::vector<Run>> runs(grids.size());
  const double nx = -std::sin(axis), ny = std::cos(axis);
  double run_length = 0.0, run_moment = 0.0;
  std::vector<Vec3> run_points;
  auto close_run = [&](int body) {
    if (run_length >= kLongRun) {
      runs[static_cast<std::size_t>(body)].push_back({run_moment / run_length, std::move(run_points)});
    }
    run_length = run_moment = 0.0;
    run_points.clear();
  };
  along = 0.0;
  std::optional<Segment> previous;
  for_each_segment(path, grids, [&](const Segment& s) {
    if (previous && previous->piece != s.piece) close_run(previous->body);
    if (axial_difference(s.angle, axis) <= kAxisTolerance) {
      along += s.length;
      run_length += s.length;
      run_moment += s.length * (nx * s.x + ny * s.y);
      run_points.push_back(s.mid);
    } else {
      close_run(s.body);
    }
    previous = s;
  });
  if (previous) close_run(previous->body);
  return runs;
}

// Neighbouring strips: positions closer than half a pad are one strip passed twice. The
// gap between two strips is measured on the skin, not in the top-down view (which
// shortens it on a dome's slopes): the median over one strip's points of the distance to
// the nearest point of the next (a k-d tree: O(n log n) however many points a session
// piles into two strips). Returns the median gap in mm (0: fewer than two strips).
double strip_spacing_mm(std::vector<std::vector<Run>>& runs, double pad_radius) {
  std::vector<double> gaps;
  for (auto& body_runs : runs) {
    std::sort(body_runs.begin(), body_runs.end(), [](const Run& a, const Run& b) { return a.position < b.position; });
    std::vector<std::vector<Vec3>> strips;
    double last = 0.0;
    for (std::size_t k = 0; k < body_runs.size(); ++k) {
      if (k == 0 || body_runs[k].position - last > 0.5 * pad_radius) strips.emplace_back();
      strips.back().insert(strips.back().end(), body_runs[k].points.begin(), body_runs[k].points.end());
      last = body_runs[k].position;
    }
    for (std::size_t k = 1; k < strips.size(); ++k) gaps.push_back(median(nearest_distances(strips[k - 1], strips[k])));
  }
  return 1000.0 * median(gaps);
}

}  // namespace

SearchPattern measure_pattern(const std::vector<PathPoint>& path, const std::vector<const ContourGrid*>& grids,
                              double pad_radius) {
  SearchPattern out;
  measure_length(path, out);
  if (out.path_length_m <= 0.0) return out;
  double total = 0.0;
  const std::optional<double> axis = dominant_axis(path, grids, total);
  if (!axis) return out;
  double along = 0.0;
  std::vector<std::vector<Run>> runs = runs_along(path, grids, *axis, along);
  out.strip_fraction = along / total;
  out.strip_spacing_mm = strip_spacing_mm(runs, pad_radius);
  return out;
}

}  // namespace palpa::score::detail

namespace palpa::score {

std::string to_string(PatternKind kind) {
  switch (kind) {
    case PatternKind::Sporadic: return "sporadic";
    case PatternKind::Localized: return "localized";
    case PatternKind::Thorough: return "thorough";
    case PatternKind::Efficient: return "efficient";
    case PatternKind::None: break;
  }
  return "none";
}

}  // namespace palpa::score

namespace palpa::score::detail {

PatternKind classify_pattern(const SearchPattern& pattern, bool any_contact, double coverage, bool compact,
                            const Thresholds& thresholds) {
  if (!any_contact) return PatternKind::None;
  if (coverage >= thresholds.min_coverage) {
    const bool strips = pattern.strip_fraction >= kEfficientStripFraction;
    return strips && pattern.revisit_fraction <= kEfficientRevisitFraction ? PatternKind::Efficient
                                                                           : PatternKind::Thorough;
  }
  if (coverage < kLocalizedCoverage && compact) return PatternKind::Localized;
  return PatternKind::Sporadic;
}

}  // namespace palpa::score::detail
