#include "palpa/scripted/scripted_trainee.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "surface_frame.hpp"
#include "palpa/vec3.hpp"

namespace palpa::scripted {

using detail::frame_at;

std::string_view to_string(Style style) {
  switch (style) {
    case Style::Expert: return "expert";
    case Style::Sloppy: return "sloppy";
    case Style::Light: return "light";
  }
  return "expert";
}

std::optional<Style> style_from_string(std::string_view name) {
  if (name == "expert") return Style::Expert;
  if (name == "sloppy") return Style::Sloppy;
  if (name == "light") return Style::Light;
  return std::nullopt;
}

std::vector<ExamRect> whole_top_contours(const scene::Scene& scene) {
  std::vector<ExamRect> out;
  for (std::size_t b = 0; b < scene.size(); ++b) out.push_back({b, 0.0, 1.0, 0.0, 1.0});
  return out;
}

StyleParameters parameters_for(Style style) {
  StyleParameters p;  // the defaults are the expert's
  switch (style) {
    case Style::Expert: break;
    case Style::Sloppy:
      // Strips far wider than the finger pad, one in three skipped, one medium press.
      p.strip_spacing = 0.038;
      p.spot_step = 0.012;
      p.skip_every = 3;
      p.levels = {0.30, 0.0, 0.0};
      p.level_count = 1;
      p.false_marks_min = 2;
      p.false_marks_max = 3;
      p.slide = false;  // hops from spot to spot
      break;
    case Style::Light:
      // The expert's coverage, but it never presses past a fifth of the tissue.
      p.levels = {0.08, 0.15, 0.0};
      p.level_count = 2;
      p.slide_level = 0.08;
      break;
  }
  return p;
}

namespace {

constexpr int kArcSamples = 64;     // per parameter line, for arc lengths
constexpr double kTransitStep = 0.005;  // m between the lifted waypoints of a glide
constexpr int kMaxTransitPoints = 48;
constexpr double kBodyChangeLift = 0.03;  // m above the surface when moving to another body
constexpr std::size_t kDetourCapacity = 8192;
// Over the force limit by more than this (N, e.g. the tissue creeping under a held
// press), the press backs off by a step each tick until it is back under.
constexpr double kBackoffMargin = 0.2;
constexpr double kBackoffStep = 2e-5;  // m per tick
constexpr double kNoCap = std::numeric_limits<double>::infinity();
// A sloppy trainee's false mark goes where nothing was felt: a spot at most this much
// stiffer than its neighbourhood (tissue's own spread, under any suspicion ratio) ...
constexpr double kPlainSpotRatio = 1.1;
// ... and clear of every spot this much stiffer (what a search press may have felt of a
// tumour, well under the 1.3 suspicion ratio), so a false mark never lands on one.
constexpr double kFeltSpotRatio = 1.15;

// Cumulative arc length of the top contour along a parameter line (kArcSamples + 1 values).
template <typename Point>
std::vector<double> arc_table(Point&& point) {
  std::vector<double> s(kArcSamples + 1, 0.0);
  Vec3 prev = point(0.0);
  for (int k = 1; k <= kArcSamples; ++k) {
    const Vec3 p = point(static_cast<double>(k) / kArcSamples);
    s[static_cast<std::size_t>(k)] = s[static_cast<std::size_t>(k - 1)] + (p - prev).norm();
    prev = p;
  }
  return s;
}

// The line parameter in [0, 1] at arc length `length` of a table.
double invert_arc(const std::vector<double>& s, double length) {
  const auto it = std::lower_bound(s.begin(), s.end(), length);
  if (it == s.begin()) return 0.0;
  if (it == s.end()) return 1.0;
  const auto k = static_cast<std::size_t>(it - s.begin());
  const double a = s[k] > s[k - 1] ? (length - s[k - 1]) / (s[k] - s[k - 1]) : 0.0;
  return (static_cast<double>(k - 1) + a) / kArcSamples;
}

std::uint64_t splitmix(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

ScriptedTrainee::ScriptedTrainee(const scene::Scene& scene, const std::vector<ExamRect>& region, Style style,
                                 std::uint64_t seed)
    : ScriptedTrainee(scene, region, style, parameters_for(style), seed) {}

ScriptedTrainee::ScriptedTrainee(const scene::Scene& scene, const std::vector<ExamRect>& region, Style style,
                                 const StyleParameters& parameters, std::uint64_t seed)
    : scene_(&scene), style_(style), params_(parameters), rng_state_(seed) {
  caps_.name = "scripted trainee (";
  caps_.name += to_string(style);
  caps_.name += ")";
  caps_.max_force = 30.0;
  caps_.force_output = true;
  if (scene.size() > 0) {
    Vec3 lo = scene.body(0).bounds.lo, hi = scene.body(0).bounds.hi;
    for (std::size_t b = 1; b < scene.size(); ++b) {
      lo = lo.cwiseMin(scene.body(b).bounds.lo);
      hi = hi.cwiseMax(scene.body(b).bounds.hi);
    }
    caps_.workspace_center = (lo + hi) / 2.0;
    caps_.workspace_radius = (hi - lo).norm() / 2.0 + kBodyChangeLift;
  }
  plan(region);
  const std::size_t n = spots_.size();
  stiffness_.assign(n, 0.0);
  held_.assign(n, 0.0);
  pressed_force_.assign(n, 0.0);
  measure_time_.assign(n, -1.0);
  curve_.assign(n * kDepthGrid, 0.0);
  cap_ = kNoCap;
  ratio_.assign(n, 0.0);
  layer_factor_.resize(n);
  for (std::size_t i = 0; i < n; ++i) layer_factor_[i] = layer_factor(spots_[i].body, spots_[i].thickness);
  suspicious_.assign(n, 0);
  scratch_.reserve(n);
  group_.reserve(n);
  findings_.reserve(n);
  events_.reserve(n + 8);
  detour_.reserve(kDetourCapacity);
  if (!scan_.empty()) from_ = scan_.front().position;
  last_pose_ = from_;
}

double ScriptedTrainee::max_depth_fraction() const {
  const double deepest = params_.levels[static_cast<std::size_t>(params_.level_count - 1)];
  return deepest * params_.repalpate_factor;  // a re-palpation presses hardest
}

// --- planning (constructor only) ---------------------------------------------------

void ScriptedTrainee::plan(const std::vector<ExamRect>& region) {
  int strip = 0;
  for (const auto& rect : region) {
    if (rect.body < scene_->size()) plan_rect(rect, strip);
  }
  strip_first_.push_back(static_cast<int>(spots_.size()));

  // The scan: glide (lifted) to the first spot of each strip and touch down; press at each
  // spot and slide in contact to the next (or lift and glide, when the style does not
  // slide); lift at the strip's end and note it.
  const double v = params_.press_speed;
  double depth = 0.0;  // below the current spot's top, where the last press left the probe
  for (std::size_t i = 0; i < spots_.size(); ++i) {
    const Spot& s = spots_[i];
    const bool strip_starts = i == 0 || spots_[i - 1].strip != s.strip;
    const bool strip_ends = i + 1 == spots_.size() || spots_[i + 1].strip != s.strip;
    const bool slide_on = params_.slide && !strip_ends;
    if (strip_starts || !params_.slide) {
      const Vec3 above = s.top + params_.lift * s.normal;
      if (i == 0) {
        scan_.push_back({above, 0.0, Action::None, -1});
      } else {
        const Spot& p = spots_[i - 1];
        add_glide(scan_, p.body, p.u, p.v, s.body, s.u, s.v, scan_.back().position);
      }
      scan_.push_back(press_to(s.top, s.normal, 0.0, params_.lift / v, params_.force_limit));
      depth = 0.0;
    }
    const double leave = slide_on ? params_.slide_level * s.thickness : 0.0;
    add_press(scan_, s, static_cast<int>(i), depth, leave);
    if (slide_on) {
      add_slide(scan_, s, spots_[i + 1]);
      depth = params_.slide_level * spots_[i + 1].thickness;
    } else {
      scan_.push_back({s.top + params_.lift * s.normal, params_.lift / v, Action::None, -1});
    }
    if (strip_ends) scan_.push_back({scan_.back().position, 0.0, Action::StripEnd, s.strip});
  }
  if (!scan_.empty()) scan_.push_back({scan_.back().position, 0.0, Action::End, -1});
  for (const auto& w : scan_) scan_duration_ += w.duration;
}

void ScriptedTrainee::plan_rect(const ExamRect& rect, int& strip) {
  const auto& body = scene_->body(rect.body).body;
  auto uv = [&](bool along_v, double a, double c) {
    // a: position along the strips, c: across them, both in [0, 1] of the rectangle.
    const double su = along_v ? c : a, sv = along_v ? a : c;
    return std::array<double, 2>{rect.u0 + (rect.u1 - rect.u0) * su, rect.v0 + (rect.v1 - rect.v0) * sv};
  };
  auto top = [&](const std::array<double, 2>& p) { return frame_at(body, p[0], p[1]).top; };
  // Vertical strips run along the long axis of the region (MammaCare: up and down).
  const double length_u = arc_table([&](double x) { return top(uv(false, x, 0.5)); }).back();
  const double length_v = arc_table([&](double x) { return top(uv(true, x, 0.5)); }).back();
  const bool along_v = length_v >= length_u;

  // Strips evenly spaced across, measured on the widest cross line so they are never
  // farther apart than the spacing.
  std::vector<double> across;
  for (int k = 0; k <= 8; ++k) {
    const double a = 0.1 + 0.8 * k / 8.0;
    auto table = arc_table([&](double c) { return top(uv(along_v, a, c)); });
    if (across.empty() || table.back() > across.back()) across = std::move(table);
  }
  const double width = across.back();
  const int strips = std::max(1, static_cast<int>(std::ceil(width / params_.strip_spacing - 1e-9)));
  for (int k = 0; k < strips; ++k) {
    if (params_.skip_every > 0 && k % params_.skip_every == params_.skip_every - 1) continue;
    const double c = invert_arc(across, (k + 0.5) * width / strips);
    const auto along = arc_table([&](double a) { return top(uv(along_v, a, c)); });
    const double length = along.back();
    const int count = std::max(1, static_cast<int>(std::ceil(length / params_.spot_step - 1e-9)));
    if (static_cast<int>(strip_first_.size()) <= strip) strip_first_.push_back(static_cast<int>(spots_.size()));
    for (int j = 0; j < count; ++j) {
      // Up one strip, down the next.
      const int jj = strip % 2 == 0 ? j : count - 1 - j;
      const double a = invert_arc(along, (jj + 0.5) * length / count);
      const auto p = uv(along_v, a, c);
      const auto f = frame_at(body, p[0], p[1]);
      if (!f.ok) continue;
      spots_.push_back({rect.body, p[0], p[1], f.top, f.normal, 2.0 * f.radius, strip});
    }
    if (static_cast<int>(spots_.size()) > strip_first_.back()) {
      ++strip;
    } else {
      strip_first_.pop_back();  // no usable spot on this line
    }
  }
}

ScriptedTrainee::Waypoint ScriptedTrainee::press_to(const Vec3& top, const Vec3& normal, double indentation,
                                                    double duration, double force_limit, Action action, int index) {
  Waypoint w;
  w.position = top - indentation * normal;
  w.duration = duration;
  w.action = action;
  w.index = index;
  w.press = true;
  w.indentation = indentation;
  w.normal = normal;
  w.force_limit = force_limit;
  return w;
}

void ScriptedTrainee::add_press(std::vector<Waypoint>& out, const Spot& spot, int spot_index, double from_depth,
                                double to_depth) const {
  const double v = params_.press_speed;
  const double limit = params_.force_limit;
  double depth = from_depth;
  for (int l = 0; l < params_.level_count; ++l) {
    const double target = params_.levels[static_cast<std::size_t>(l)] * spot.thickness;
    out.push_back(press_to(spot.top, spot.normal, target, std::abs(target - depth) / v, limit));
    out.back().spot = spot_index;
    const bool deepest = l + 1 == params_.level_count;
    out.push_back(press_to(spot.top, spot.normal, target, params_.hold, limit,
                           deepest ? Action::Measure : Action::None, deepest ? spot_index : -1));
    out.back().spot = spot_index;
    depth = target;
  }
  out.push_back(press_to(spot.top, spot.normal, to_depth, std::abs(depth - to_depth) / v, limit));
}

void ScriptedTrainee::add_slide(std::vector<Waypoint>& out, const Spot& from, const Spot& to) const {
  const auto& mb = scene_->body(to.body).body;
  const Vec3 start = from.top - params_.slide_level * from.thickness * from.normal;
  const Vec3 end = to.top - params_.slide_level * to.thickness * to.normal;
  const int n = std::clamp(static_cast<int>(std::ceil((end - start).norm() / kTransitStep)), 1, kMaxTransitPoints);
  Vec3 prev = start;
  for (int k = 1; k <= n; ++k) {
    // Along the strip's parameter line at the slide level of the local thickness.
    const double a = static_cast<double>(k) / n;
    Vec3 p = end;
    if (k < n) {
      const auto f = frame_at(mb, from.u + a * (to.u - from.u), from.v + a * (to.v - from.v));
      p = f.top - params_.slide_level * 2.0 * f.radius * f.normal;
    }
    out.push_back({p, (p - prev).norm() / params_.move_speed, Action::None, -1});
    prev = p;
  }
}

void ScriptedTrainee::add_transit(std::vector<Waypoint>& out, std::size_t body, double u0, double v0, double u1,
                                  double v1, const Vec3& from) const {
  const auto& mb = scene_->body(body).body;
  const auto end = frame_at(mb, u1, v1);
  const Vec3 target = end.top + params_.lift * end.normal;
  const int n = std::clamp(static_cast<int>(std::ceil((target - from).norm() / kTransitStep)), 1, kMaxTransitPoints);
  Vec3 prev = from;
  for (int k = 1; k <= n; ++k) {
    // Lifted over the surface along the parameter line, so a glide never cuts through
    // the body between spots.
    const double a = static_cast<double>(k) / n;
    Vec3 p = target;
    if (k < n) {
      const auto f = frame_at(mb, u0 + a * (u1 - u0), v0 + a * (v1 - v0));
      p = f.top + params_.lift * f.normal;
    }
    out.push_back({p, (p - prev).norm() / params_.move_speed, Action::None, -1});
    prev = p;
  }
}

void ScriptedTrainee::add_glide(std::vector<Waypoint>& out, std::size_t from_body, double u0, double v0,
                                std::size_t to_body, double u1, double v1, const Vec3& from) const {
  if (from_body == to_body) {
    add_transit(out, to_body, u0, v0, u1, v1, from);
    return;
  }
  const auto a = frame_at(scene_->body(from_body).body, u0, v0);
  const auto b = frame_at(scene_->body(to_body).body, u1, v1);
  Vec3 prev = from;
  for (const Vec3& p : {Vec3(a.top + kBodyChangeLift * a.normal), Vec3(b.top + kBodyChangeLift * b.normal),
                        Vec3(b.top + params_.lift * b.normal)}) {
    out.push_back({p, (p - prev).norm() / params_.move_speed, Action::None, -1});
    prev = p;
  }
}

// --- performing (allocation-free) ----------------------------------------------------

engine::DeviceStatus ScriptedTrainee::read(double t, engine::DevicePose& pose) noexcept {
  pose.buttons = 0;
  for (;;) {
    if (in_detour_ && next_detour_ >= detour_.size()) {
      in_detour_ = false;
      detour_.clear();  // keeps its capacity
      next_detour_ = 0;
    }
    const Waypoint* w = nullptr;
    if (in_detour_) {
      w = &detour_[next_detour_];
    } else if (next_scan_ < scan_.size()) {
      w = &scan_[next_scan_];
    }
    if (w == nullptr) {
      if (!finished_) {
        finished_ = true;
        finish_time_ = segment_start_;
      }
      pose.position = from_;
      return engine::DeviceStatus::Ok;
    }
    if (w->press) {
      regulate(*w);
    } else {
      cap_ = kNoCap;  // a new press starts uncapped
    }
    if (t < segment_start_ + w->duration) {
      const double a = (t - segment_start_) / w->duration;
      pose.position = from_ + std::clamp(a, 0.0, 1.0) * (target_of(*w) - from_);
      last_pose_ = pose.position;
      return engine::DeviceStatus::Ok;
    }
    const Waypoint done = *w;
    segment_start_ += done.duration;
    from_ = target_of(done);
    if (in_detour_) {
      ++next_detour_;
    } else {
      ++next_scan_;
    }
    complete(done, segment_start_);
  }
}

Vec3 ScriptedTrainee::target_of(const Waypoint& w) const noexcept {
  if (!w.press || w.indentation <= cap_) return w.position;
  return w.position + (w.indentation - cap_) * w.normal;
}

void ScriptedTrainee::regulate(const Waypoint& w) noexcept {
  const double felt = force_.norm();
  const Vec3 top = w.position + w.indentation * w.normal;
  double reached = (top - last_pose_).dot(w.normal);
  if (w.spot >= 0) {
    // The force-depth curve while pressing in: |F| where the depth crossed each grid
    // point, interpolated between the last two ticks.
    const auto spot = static_cast<std::size_t>(w.spot);
    const double fraction = reached / spots_[spot].thickness;
    if (curve_spot_ != w.spot) {
      curve_spot_ = w.spot;
      curve_fraction_ = fraction;
      curve_force_ = felt;
    } else if (fraction > curve_fraction_) {
      for (int k = 1; k < kDepthGrid; ++k) {
        const double g = k * kDepthStep;
        if (g <= curve_fraction_ || g > fraction) continue;
        const double a = (g - curve_fraction_) / (fraction - curve_fraction_);
        curve_[spot * kDepthGrid + static_cast<std::size_t>(k)] = curve_force_ + a * (felt - curve_force_);
      }
      curve_fraction_ = fraction;
      curve_force_ = felt;
    }
  }
  // Stop where the next tick would reach the limit at the force's current rise (a person
  // slows down before the limit, too), so the peak overshoots it by little.
  if (felt + std::max(0.0, felt - previous_felt_) < w.force_limit) return;
  // force_ was felt at last_pose_: hold that indentation (or a little less while the
  // force stays over the limit) for the rest of the press.
  if (felt > w.force_limit + kBackoffMargin) reached -= kBackoffStep;
  cap_ = std::min(cap_, std::max(0.0, reached));
}

double ScriptedTrainee::stiffness_at(std::size_t spot, int k) const noexcept {
  const double f = curve_[spot * kDepthGrid + static_cast<std::size_t>(k)];
  return f > 0.0 ? f / (k * kDepthStep * spots_[spot].thickness) / layer_factor_[spot] : 0.0;
}

bool ScriptedTrainee::in_pa(std::size_t body) const noexcept {
  const auto& b = scene_->body(body);
  return b.layer.has_value() && b.force_model == mat::ForceModel::Calibrated;
}

double ScriptedTrainee::layer_factor(std::size_t body, double thickness) const noexcept {
  if (!in_pa(body) || !(thickness > 0.0)) return 1.0;
  const double f = (*scene_->body(body).layer)(1.0, thickness);
  return f > 0.0 ? f : 1.0;
}

int ScriptedTrainee::deepest_grid(std::size_t spot) const noexcept {
  for (int k = kDepthGrid - 1; k >= 1; --k) {
    if (curve_[spot * kDepthGrid + static_cast<std::size_t>(k)] > 0.0) return k;
  }
  return -1;
}

engine::DeviceStatus ScriptedTrainee::write_force(const Vec3& force) noexcept {
  previous_felt_ = force_.norm();
  force_ = force;
  return engine::DeviceStatus::Ok;
}

bool ScriptedTrainee::pop_event(session::Event& event) noexcept {
  if (events_read_ >= events_.size()) return false;
  event = events_[events_read_++];
  return true;
}

void ScriptedTrainee::push_mark(double t, const Vec3& position) noexcept {
  if (events_.size() >= events_.capacity()) return;  // never allocate in the haptic thread
  session::Event e;
  e.t = t;
  e.kind = session::EventKind::Mark;
  e.mark = next_mark_++;
  e.position = to_array(position);
  events_.push_back(e);
}

void ScriptedTrainee::complete(const Waypoint& w, double t) noexcept {
  switch (w.action) {
    case Action::None: break;
    case Action::Measure:
    {
      // The hold has lasted long enough for the force to settle: judge the press by it and
      // the indentation actually held.
      const auto i = static_cast<std::size_t>(w.index);
      held_[i] = std::min(w.indentation, cap_);
      pressed_force_[i] = force_.norm();
      measure_time_[i] = t;
      if (held_[i] > 0.0) stiffness_[i] = pressed_force_[i] / held_[i];
      break;
    }
    case Action::StripEnd: {
      // A strip is judged once the next one is done, so its neighbourhood lies on both
      // sides of it; the last strip is judged with what there is.
      // The strip just done is judged provisionally (one-sided neighbourhood): its spots
      // may join a finding of the previous strip, so the mark falls between the two
      // strips when the mass lies between them, but they cannot start one.
      const int last = static_cast<int>(strip_first_.size()) - 2;
      if (w.index >= 1) judge_strip(w.index - 1, false);
      judge_strip(w.index, w.index != last);
      const int end_spot = strip_first_[static_cast<std::size_t>(w.index) + 1] - 1;
      find_groups(static_cast<std::size_t>(end_spot));
      break;
    }
    case Action::Repalpate: {
      // Compared with the neighbourhood at the same depth fraction.
      Finding& f = findings_[static_cast<std::size_t>(w.index)];
      const double held = std::min(w.indentation, cap_);
      if (held > 0.0) f.felt = force_.norm() / held;
      // At the re-palpation's depth, or the deepest the neighbours' presses reached when it
      // went deeper than they did (tissue in Pa is linear: the same stiffness at both).
      auto k = std::min(kDepthGrid - 1, static_cast<int>(held / (f.thickness * kDepthStep) + 1e-9));
      if (in_pa(f.body)) k = std::min(k, f.grid);
      if (k >= 1) f.reference = neighbourhood_median(f.body, f.top, k, spots_.size());
      f.felt /= layer_factor(f.body, f.thickness);
      const double confirm = in_pa(f.body) ? params_.tissue_confirm_ratio : params_.confirm_ratio;
      f.marked = f.reference > 0.0 && f.felt > confirm * f.reference;
      break;
    }
    case Action::MarkFinding: {
      const Finding& f = findings_[static_cast<std::size_t>(w.index)];
      if (f.marked) push_mark(t, w.position);
      break;
    }
    case Action::MarkFalse: push_mark(t, w.position); break;
    case Action::End: add_false_marks(); break;
  }
  if (!detour_.empty() && next_detour_ < detour_.size()) in_detour_ = true;
}

double ScriptedTrainee::neighbourhood_median(std::size_t body, const Vec3& top, int k, std::size_t exclude) noexcept {
  scratch_.clear();
  const double reach = in_pa(body) ? params_.tissue_neighbourhood : params_.neighbourhood;
  const double r2 = reach * reach;
  for (std::size_t j = 0; j < spots_.size(); ++j) {
    const Spot& o = spots_[j];
    if (j == exclude || o.body != body || o.thickness < params_.min_thickness) continue;
    const double kj = stiffness_at(j, k);
    if (kj > 0.0 && (o.top - top).squaredNorm() < r2) scratch_.push_back(kj);
  }
  if (scratch_.size() < 3) return 0.0;
  const auto mid = scratch_.begin() + static_cast<std::ptrdiff_t>(scratch_.size() / 2);
  std::nth_element(scratch_.begin(), mid, scratch_.end());
  return *mid;
}

void ScriptedTrainee::judge_strip(int strip, bool provisional) noexcept {
  const auto first = static_cast<std::size_t>(strip_first_[static_cast<std::size_t>(strip)]);
  const auto last = static_cast<std::size_t>(strip_first_[static_cast<std::size_t>(strip) + 1]);
  for (std::size_t i = first; i < last; ++i) {
    if (suspicious_[i] == kTaken) continue;
    suspicious_[i] = kPlain;
    ratio_[i] = 0.0;
    if (stiffness_[i] <= 0.0 || spots_[i].thickness < params_.min_thickness) continue;
    // Stiffness at the deepest depth this press reached, against the neighbours' at
    // the same depth.
    const int k = deepest_grid(i);
    if (k < 1) continue;
    const double median = neighbourhood_median(spots_[i].body, spots_[i].top, k, i);
    if (median <= 0.0) continue;
    ratio_[i] = stiffness_at(i, k) / median;
    const double suspicion = in_pa(spots_[i].body) ? params_.tissue_suspicion_ratio : params_.suspicion_ratio;
    if (ratio_[i] > suspicion) suspicious_[i] = provisional ? kMayJoin : kSuspicious;
  }
}

void ScriptedTrainee::find_groups(std::size_t at) noexcept {
  const Spot& here = spots_[at];
  double cu = here.u, cv = here.v;
  std::size_t cbody = here.body;
  Vec3 cursor = here.top + params_.lift * here.normal;
  bool any = false;
  const double g2 = params_.group_distance * params_.group_distance;
  for (std::size_t seed = 0; seed < spots_.size(); ++seed) {
    if (suspicious_[seed] != kSuspicious) continue;
    // Single linkage: every suspicious spot within group_distance of the group joins it.
    group_.clear();
    group_.push_back(static_cast<int>(seed));
    suspicious_[seed] = kTaken;
    for (std::size_t k = 0; k < group_.size(); ++k) {
      const Spot& a = spots_[static_cast<std::size_t>(group_[k])];
      for (std::size_t j = 0; j < spots_.size(); ++j) {
        if ((suspicious_[j] != kSuspicious && suspicious_[j] != kMayJoin) || spots_[j].body != a.body) continue;
        if ((spots_[j].top - a.top).squaredNorm() < g2) {
          suspicious_[j] = kTaken;
          group_.push_back(static_cast<int>(j));
        }
      }
    }
    // The stiffness-weighted centroid (by how much stiffer each spot felt).
    double w = 0.0, u = 0.0, v = 0.0, searched = 0.0;
    int grid = 0;
    for (int g : group_) {
      const auto i = static_cast<std::size_t>(g);
      searched = std::max(searched, pressed_force_[i]);
      grid = std::max(grid, deepest_grid(i));
      const double wi = ratio_[i] - 1.0;
      w += wi;
      u += wi * spots_[i].u;
      v += wi * spots_[i].v;
    }
    const std::size_t body = spots_[seed].body;
    u /= w;
    v /= w;
    const auto f = frame_at(scene_->body(body).body, u, v);
    // A finding next to an earlier one is the same mass felt again from the next strip.
    bool known = false;
    for (const auto& old : findings_) {
      if (old.body == body && (old.top - f.top).squaredNorm() < g2) known = true;
    }
    if (known || !f.ok || findings_.size() >= findings_.capacity() || !detour_room(2 * kMaxTransitPoints + 16)) {
      continue;
    }
    const int index = static_cast<int>(findings_.size());
    findings_.push_back({body, grid, u, v, f.top, 2.0 * f.radius, 0.0, 0.0, false});

    // Re-palpate the finding's centre a little harder than the search presses there
    // (deeper, and up to repalpate_factor times the force they felt, never over the
    // limit), and mark it on the surface if it is still clearly stiffer than its
    // surroundings.
    add_glide(detour_, cbody, cu, cv, body, u, v, cursor);
    const double v_press = params_.press_speed;
    // Tissue in Pa feels the same contrast at every depth (linear elasticity): the finding
    // is re-palpated as deep as the search pressed, where its neighbours were measured.
    const double deeper = in_pa(body) ? 1.0 : params_.repalpate_factor;
    const double depth = params_.levels[static_cast<std::size_t>(params_.level_count - 1)] * deeper * 2.0 * f.radius;
    const double limit = std::min(params_.force_limit, params_.repalpate_factor * searched);
    detour_.push_back(press_to(f.top, f.normal, 0.0, params_.lift / v_press, limit));
    detour_.push_back(press_to(f.top, f.normal, depth, depth / v_press, limit));
    detour_.push_back(press_to(f.top, f.normal, depth, params_.hold, limit, Action::Repalpate, index));
    detour_.push_back(press_to(f.top, f.normal, 0.0, depth / v_press, limit, Action::MarkFinding, index));
    cursor = f.top + params_.lift * f.normal;
    detour_.push_back({cursor, params_.lift / v_press, Action::None, -1});
    cu = u;
    cv = v;
    cbody = body;
    any = true;
  }
  if (any) add_glide(detour_, cbody, cu, cv, here.body, here.u, here.v, cursor);  // back to where the scan goes on
}

void ScriptedTrainee::add_false_marks() noexcept {
  if (params_.false_marks_max <= 0 || spots_.empty()) return;
  const int span = params_.false_marks_max - params_.false_marks_min + 1;
  const int count = params_.false_marks_min + static_cast<int>(splitmix(rng_state_) % static_cast<std::uint64_t>(span));
  const double clear2 = params_.false_mark_clearance * params_.false_mark_clearance;
  group_.clear();
  const Spot& here = spots_.back();
  double cu = here.u, cv = here.v;
  std::size_t cbody = here.body;
  Vec3 cursor = here.top + params_.lift * here.normal;
  for (int m = 0; m < count; ++m) {
    // A spot where nothing was felt, far from anything that was and from the other marks.
    const std::size_t start = splitmix(rng_state_) % spots_.size();
    for (std::size_t k = 0; k < spots_.size(); ++k) {
      const std::size_t i = (start + k) % spots_.size();
      const Spot& s = spots_[i];
      if (stiffness_[i] <= 0.0 || ratio_[i] <= 0.0 || ratio_[i] > kPlainSpotRatio) continue;
      bool clear = true;
      for (std::size_t j = 0; j < spots_.size() && clear; ++j) {
        if (ratio_[j] > kFeltSpotRatio && spots_[j].body == s.body && (spots_[j].top - s.top).squaredNorm() < clear2) clear = false;
      }
      for (int g : group_) {
        const Spot& o = spots_[static_cast<std::size_t>(g)];
        if (o.body == s.body && (o.top - s.top).squaredNorm() < clear2) clear = false;
      }
      if (!clear || !detour_room(kMaxTransitPoints + 4)) continue;
      group_.push_back(static_cast<int>(i));
      add_glide(detour_, cbody, cu, cv, s.body, s.u, s.v, cursor);
      detour_.push_back({s.top, params_.lift / params_.press_speed, Action::MarkFalse, static_cast<int>(i)});
      cursor = s.top + params_.lift * s.normal;
      detour_.push_back({cursor, params_.lift / params_.press_speed, Action::None, -1});
      cu = s.u;
      cv = s.v;
      cbody = s.body;
      break;
    }
  }
}

}  // namespace palpa::scripted
