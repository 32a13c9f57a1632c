// Force and indentation level over time (see images.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include <opencv2/core.hpp>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/plot/line_plot.hpp"
#include "palpa/report/images.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::report {
namespace {

constexpr std::size_t kMaxPoints = 2000;

/// Keeps the largest value of each run of samples, at that sample's time: peaks, which the
/// safety gate is about, survive the decimation.
void decimate_into(const std::vector<double>& t, const std::vector<double>& y, plot::Series& out) {
  const std::size_t n = std::min(t.size(), y.size());
  const std::size_t run = std::max<std::size_t>(1, (n + kMaxPoints - 1) / kMaxPoints);
  for (std::size_t begin = 0; begin < n; begin += run) {
    const std::size_t end = std::min(n, begin + run);
    std::size_t best = begin;
    for (std::size_t i = begin + 1; i < end; ++i)
      if (y[i] > y[best]) best = i;
    out.x.push_back(t[best]);
    out.y.push_back(y[best]);
  }
}

plot::Series level_line(const std::string& label, double value, double t0, double t1) {
  plot::Series s;
  s.label = label;
  s.x = {t0, t1};
  s.y = {value, value};
  s.marker = plot::Marker::None;
  return s;
}

/// The scene of the session's case, or nothing when it cannot be built.
std::unique_ptr<scene::Scene> scene_of(const session::Session& session) {
  try {
    const auto file = io::parse_case(session.info.case_document.dump(), session.info.case_source);
    return std::make_unique<scene::Scene>(scene::Scene::build(file, session.info.case_source));
  } catch (const std::exception&) {
    return nullptr;
  }
}

}  // namespace

cv::Mat force_plot(const session::Session& session, const score::Score& score) {
  const auto& samples = session.samples;
  std::vector<double> t(samples.size()), force(samples.size()), level(samples.size(), 0.0);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    t[i] = s.t;
    force[i] = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
  }
  const auto scene = samples.empty() ? nullptr : scene_of(session);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    if (s.body < 0 || !(s.depth > 0.0)) continue;
    if (!scene) {
      level[i] = s.depth * 1e3;
      continue;
    }
    if (static_cast<std::size_t>(s.body) >= scene->size()) continue;
    double channels[4];
    scene->body(static_cast<std::size_t>(s.body)).body.skeleton().evaluate(std::clamp(s.u, 0.0, 1.0),
                                                                          std::clamp(s.v, 0.0, 1.0), channels, 4);
    const double thickness = 2.0 * channels[mat::kRadius];
    level[i] = thickness > 0.0 ? s.depth / thickness : 0.0;
  }
  const double t0 = t.empty() ? 0.0 : t.front(), t1 = t.empty() ? 1.0 : std::max(t.back(), t0 + 1e-3);

  plot::LinePlot top;
  top.title = "Force on the probe";
  top.x.label = "time (s)";
  top.y.label = "|F| (N)";
  top.height = 330;
  top.x.min = t0;
  top.x.max = t1;
  top.y.min = 0.0;
  plot::Series f{"|F|", {}, {}, plot::Marker::None, true};
  decimate_into(t, force, f);
  top.series.push_back(std::move(f));
  double peak = 0.0;
  for (const double v : force) peak = std::max(peak, v);
  if (peak > 0.5 * score.thresholds.max_force)
    top.series.push_back(level_line("safety limit", score.thresholds.max_force, t0, t1));

  plot::LinePlot bottom;
  bottom.height = 330;
  bottom.x = top.x;
  bottom.y.min = 0.0;
  plot::Series l{{}, {}, {}, plot::Marker::None, true};
  decimate_into(t, level, l);
  if (scene) {
    bottom.title = "Indentation level";
    bottom.y.label = "depth / thickness";
    l.label = "level";
    bottom.series.push_back(std::move(l));
    bottom.series.push_back(level_line("light | medium", score.thresholds.light_max, t0, t1));
    bottom.series.push_back(level_line("medium | deep", score.thresholds.deep_min, t0, t1));
  } else {
    bottom.title = "Indentation depth";
    bottom.y.label = "depth (mm)";
    l.label = "depth";
    bottom.series.push_back(std::move(l));
  }
  cv::Mat image;
  cv::vconcat(plot::render(top), plot::render(bottom), image);
  return image;
}

}  // namespace palpa::report
