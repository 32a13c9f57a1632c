#include "palpa/live/live_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "../score/exam_grids.hpp"

namespace palpa::live {
namespace {

// The score stamps the pad each time the contact moved half a millimetre (sample_pass.cpp):
// the way between two snapshots is filled in at the same spacing.
constexpr double kStampMove = 0.0005;  // m
constexpr int kMaxSteps = 2000;        // a jump of a metre at most is filled in

}  // namespace

struct LiveCoverage::Impl {
  Impl(const scene::Scene& scene, const io::Thresholds& th) : thresholds(th), exam(scene, th, notes) {
    for (const auto& c : exam.coverage) seen.push_back(c.level());
  }
  io::Thresholds thresholds;
  std::vector<std::string> notes;
  score::detail::ExamGrids exam;
  std::vector<int> stamped;
  std::vector<std::vector<std::uint8_t>> seen;  // per body: the levels as of the last version
  std::uint32_t stamp_number = 0;
  // The previous contact.
  int body = -1;
  double u = 0.0, v = 0.0;
  Vec3 top = Vec3::Zero();
  std::uint8_t level = 0;

  std::uint8_t level_at(double depth, double radius) const {
    const double d = std::max(0.0, depth);
    const double ratio = radius > 0.0 ? d / (2.0 * radius) : (d > 0.0 ? 1.0 : 0.0);
    return ratio < thresholds.light_max ? 1 : ratio >= thresholds.deep_min ? 3 : 2;
  }
};

LiveCoverage::LiveCoverage(const scene::Scene& scene, const io::Thresholds& thresholds)
    : impl_(std::make_unique<Impl>(scene, thresholds)) {}

LiveCoverage::~LiveCoverage() = default;

void LiveCoverage::lift() {
  if (impl_->body >= 0) ++impl_->stamp_number;
  impl_->body = -1;
}

void LiveCoverage::stamp_at(std::size_t body, double u, double v, const Vec3& top, std::uint8_t level) {
  auto& in = *impl_;
  auto& coverage = in.exam.coverage[body];
  ++in.stamp_number;
  coverage.stamp(top, in.exam.grids[body].cell_of(u, v), level, in.thresholds.pad_radius, in.stamp_number, in.stamped);
  // Levels only rise: a cell whose level differs from the last one seen has changed.
  auto& seen = in.seen[body];
  for (int c : in.stamped) {
    const auto k = static_cast<std::size_t>(c);
    if (coverage.level()[k] == seen[k]) continue;
    seen[k] = coverage.level()[k];
    ++version_;
  }
}

void LiveCoverage::contact(int body, double u, double v, double depth) {
  auto& in = *impl_;
  const int count = static_cast<int>(in.exam.grids.size());
  if (body < 0 || body >= count || !std::isfinite(u) || !std::isfinite(v) || !std::isfinite(depth)) {
    lift();
    return;
  }
  const auto b = static_cast<std::size_t>(body);
  const auto& grid = in.exam.grids[b];
  Vec3 top;
  double radius = 0.0;
  grid.lookup(u, v, top, radius);
  const std::uint8_t level = in.level_at(depth, radius);
  if (in.body == body) {
    // The way from the previous contact, at the lower of the two levels (a slide does not
    // claim more depth than both ends reached).
    const int steps = std::min(kMaxSteps, static_cast<int>(std::ceil((top - in.top).norm() / kStampMove)));
    const std::uint8_t between = std::min(level, in.level);
    for (int k = 1; k < steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      const double uk = in.u + s * (u - in.u), vk = in.v + s * (v - in.v);
      Vec3 tk;
      double rk = 0.0;
      grid.lookup(uk, vk, tk, rk);
      stamp_at(b, uk, vk, tk, between);
    }
  }
  stamp_at(b, u, v, top, level);
  in.body = body;
  in.u = u;
  in.v = v;
  in.top = top;
  in.level = level;
}

double LiveCoverage::coverage() const {
  const auto area = score::detail::covered_area(impl_->exam);
  return area.region > 0.0 ? std::clamp(area.covered / area.region, 0.0, 1.0) : 0.0;
}

double LiveCoverage::deep_coverage() const {
  const auto area = score::detail::covered_area(impl_->exam);
  return area.region > 0.0 ? std::clamp(area.deep / area.region, 0.0, 1.0) : 0.0;
}

std::size_t LiveCoverage::bodies() const { return impl_->exam.grids.size(); }
int LiveCoverage::rows(std::size_t body) const { return impl_->exam.grids[body].rows(); }
int LiveCoverage::cols(std::size_t body) const { return impl_->exam.grids[body].cols(); }
const std::vector<Vec3>& LiveCoverage::centers(std::size_t body) const { return impl_->exam.grids[body].centers(); }
const std::vector<double>& LiveCoverage::areas(std::size_t body) const { return impl_->exam.grids[body].areas(); }
const std::vector<std::uint8_t>& LiveCoverage::levels(std::size_t body) const {
  return impl_->exam.coverage[body].level();
}

}  // namespace palpa::live
