// Force and indentation level over time (see images.hpp).
#include <string>

#include <opencv2/core.hpp>

#include "palpa/plot/line_plot.hpp"
#include "palpa/report/force_trace.hpp"
#include "palpa/report/images.hpp"

namespace palpa::report {
namespace {

plot::Series level_line(const std::string& label, double value, double t0, double t1) {
  plot::Series s;
  s.label = label;
  s.x = {t0, t1};
  s.y = {value, value};
  s.marker = plot::Marker::None;
  return s;
}

}  // namespace

cv::Mat force_plot(const session::Session& session, const score::Score& score) {
  ForceTrace trace(session, session.samples.size());
  trace.add(session.samples);
  trace.finish();
  return force_plot(trace, score);
}

cv::Mat force_plot(const ForceTrace& trace, const score::Score& score) {
  const double t0 = trace.t0(), t1 = trace.t1();
  plot::LinePlot top;
  top.title = "Force on the probe";
  top.x.label = "time (s)";
  top.y.label = "|F| (N)";
  top.height = 330;
  top.x.min = t0;
  top.x.max = t1;
  top.y.min = 0.0;
  top.series.push_back(trace.force());
  if (trace.peak_force() > 0.5 * score.thresholds.max_force)
    top.series.push_back(level_line("safety limit", score.thresholds.max_force, t0, t1));

  plot::LinePlot bottom;
  bottom.height = 330;
  bottom.x = top.x;
  bottom.y.min = 0.0;
  plot::Series l = trace.level();
  if (trace.levels_are_shares()) {
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
