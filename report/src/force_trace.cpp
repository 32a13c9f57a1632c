#include "palpa/report/force_trace.hpp"

#include <algorithm>
#include <cmath>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::report {
namespace {

constexpr std::uint64_t kMaxPoints = 2000;

/// The scene of the session's case, or nothing when it cannot be built.
std::unique_ptr<scene::Scene> scene_of(const session::Session& session) {
  try {
    const auto file = io::parse_case(session.info.case_document.dump(), session.info.case_source);
    return std::make_unique<scene::Scene>(scene::Scene::build(file, session.info.case_source));
  } catch (const std::exception&) {
    return nullptr;
  }
}

double force_of(const engine::Sample& s) {
  return std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
}

}  // namespace

ForceTrace::ForceTrace(const session::Session& head, std::uint64_t samples)
    : scene_(samples == 0 ? nullptr : scene_of(head)),
      run_(std::max<std::uint64_t>(1, (samples + kMaxPoints - 1) / kMaxPoints)) {
  force_.label = "|F|";
  force_.marker = plot::Marker::None;
  force_.line = true;
  level_.marker = plot::Marker::None;
  level_.line = true;
}

ForceTrace::~ForceTrace() = default;

double ForceTrace::level_of(const engine::Sample& s) const {
  if (s.body < 0 || !(s.depth > 0.0)) return 0.0;
  if (!scene_) return s.depth * 1e3;
  if (static_cast<std::size_t>(s.body) >= scene_->size()) return 0.0;
  double channels[4];
  scene_->body(static_cast<std::size_t>(s.body))
      .body.skeleton()
      .evaluate(std::clamp(s.u, 0.0, 1.0), std::clamp(s.v, 0.0, 1.0), channels, 4);
  const double thickness = 2.0 * channels[mat::kRadius];
  return thickness > 0.0 ? s.depth / thickness : 0.0;
}

void ForceTrace::add(std::span<const engine::Sample> samples) {
  for (const auto& s : samples) {
    if (seen_++ == 0) t0_ = s.t;
    last_t_ = s.t;
    const double f = force_of(s), l = level_of(s);
    peak_ = std::max(peak_, f);
    // The first largest of each run, as force_plot always chose.
    if (in_run_ == 0 || f > best_force_.y) best_force_ = {s.t, f};
    if (in_run_ == 0 || l > best_level_.y) best_level_ = {s.t, l};
    if (++in_run_ == run_) finish();
  }
}

void ForceTrace::finish() {
  if (in_run_ == 0) return;
  force_.x.push_back(best_force_.t);
  force_.y.push_back(best_force_.y);
  level_.x.push_back(best_level_.t);
  level_.y.push_back(best_level_.y);
  in_run_ = 0;
}

std::unique_ptr<ForceTrace> read_force_trace(const std::filesystem::path& path) {
  session::SampleStream stream(path);
  auto trace = std::make_unique<ForceTrace>(stream.head(), stream.declared_count());
  for (auto block = stream.next(); !block.empty(); block = stream.next()) trace->add(block);
  trace->finish();
  return trace;
}

double ForceTrace::t1() const { return seen_ == 0 ? 1.0 : std::max(last_t_, t0_ + 1e-3); }

}  // namespace palpa::report
