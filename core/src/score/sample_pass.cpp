#include "sample_pass.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::score::detail {
namespace {

constexpr double kStampMove = 0.0005;  // m the contact moves before the pad is stamped again
// A gap in the recording longer than this many sample periods does not count as contact.
constexpr double kMaxGapPeriods = 2.0;
constexpr double kDefaultRateHz = 1000.0;  // a session that does not state its rate

}  // namespace

SamplePass::SamplePass(ExamGrids& exam, const std::vector<Landing>& mark_tops, const Timeline& timeline,
                       const Thresholds& thresholds, double rate_hz)
    : exam_(exam),
      mark_tops_(mark_tops),
      tl_(timeline),
      th_(thresholds),
      rate_(rate_hz > 0 ? rate_hz : kDefaultRateHz),
      dt_cap_(kMaxGapPeriods / rate_),
      palpate2_(thresholds.palpate_radius * thresholds.palpate_radius) {}

void SamplePass::run(std::span<const engine::Sample> samples) {
  add(samples);
  finish();
}

void SamplePass::add(std::span<const engine::Sample> samples) {
  if (samples.empty()) return;
  if (held_) measure(*held_, samples.front().t - held_->t);
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) measure(samples[k], samples[k + 1].t - samples[k].t);
  held_ = samples.back();
  sample_count += samples.size();
  last_t = samples.back().t;
}

void SamplePass::finish() {
  if (held_) measure(*held_, 1.0 / rate_);
  held_.reset();
  flush();
}

// One sample; `dt_to_next` is the step to the next sample (one period for the last).
void SamplePass::measure(const engine::Sample& s, double dt_to_next) {
  const int body_count = static_cast<int>(exam_.grids.size());
  const double force = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
  peak_force_n = std::max(peak_force_n, force);
  const bool active = is_active(s);
  if (active && s.body >= body_count) ++ignored;
  // Non-finite parameters cannot be placed on the grid: such a sample is not contact.
  const bool contact = active && s.body >= 0 && s.body < body_count && std::isfinite(s.u) && std::isfinite(s.v);
  if (!contact) {
    lift_off();
    return;
  }
  touch(s, std::clamp(dt_to_next, 0.0, dt_cap_), force);
}

double SamplePass::palpate_search_ratio() const {
  if (near_count_ == 0 || search_count_ == 0 || !(search_sum_ > 0.0)) return 0.0;
  return (near_sum_ / double(near_count_)) / (search_sum_ / double(search_count_));
}

// Within [start, end], outside every pause, and not a device fault.
bool SamplePass::is_active(const engine::Sample& s) {
  while (pause_index_ < tl_.pauses.size() && tl_.pauses[pause_index_].second <= s.t) ++pause_index_;
  const bool paused = pause_index_ < tl_.pauses.size() && tl_.pauses[pause_index_].first <= s.t;
  return s.t >= tl_.start && s.t <= tl_.end && !paused && !s.fault;
}

void SamplePass::lift_off() {
  if (was_contact_) {
    flush();
    ++stamp_number_;  // lifting off ends every cell's visit
    ++piece_;
  }
  was_contact_ = false;
}

void SamplePass::touch(const engine::Sample& s, double dt, double force) {
  look_up(s);
  const std::uint8_t level = level_at(s);
  (level == 1 ? pressure.light_s : level == 2 ? pressure.medium_s : pressure.deep_s) += dt;
  contact_time_s += dt;
  add_force_near_marks(force);
  stamp(s, level);
  pending_dwell_ += dt;
  pending_peak_ = std::max(pending_peak_, force);
  was_contact_ = true;
}

void SamplePass::look_up(const engine::Sample& s) {
  if (s.body == cache_body_ && s.u == cache_u_ && s.v == cache_v_) return;
  exam_.grids[static_cast<std::size_t>(s.body)].lookup(s.u, s.v, cache_top_, cache_radius_);
  cache_body_ = s.body;
  cache_u_ = s.u;
  cache_v_ = s.v;
}

// Pressure level from the indentation as a share of the local thickness 2 r.
std::uint8_t SamplePass::level_at(const engine::Sample& s) const {
  const double depth = std::max(0.0, s.depth);
  const double ratio = cache_radius_ > 0.0 ? depth / (2.0 * cache_radius_)
                                           : (depth > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  return ratio < th_.light_max ? 1 : ratio >= th_.deep_min ? 3 : 2;
}

void SamplePass::add_force_near_marks(double force) {
  bool near = false;
  for (const auto& m : mark_tops_) near = near || (m.body >= 0 && (m.top - cache_top_).squaredNorm() <= palpate2_);
  (near ? near_sum_ : search_sum_) += force;
  ++(near ? near_count_ : search_count_);
}

// A new stamp when contact starts, changes body or level, or moves kStampMove.
void SamplePass::stamp(const engine::Sample& s, std::uint8_t level) {
  const bool new_piece = was_contact_ && have_stamp_ && s.body != stamp_body_;
  if (new_piece) ++piece_;
  if (have_stamp_ && was_contact_ && !new_piece && level == stamp_level_ &&
      !((cache_top_ - stamp_top_).squaredNorm() > kStampMove * kStampMove))
    return;
  flush();
  if (new_piece) ++stamp_number_;
  ++stamp_number_;
  const auto b = static_cast<std::size_t>(s.body);
  const int cell = exam_.grids[b].cell_of(s.u, s.v);
  exam_.coverage[b].stamp(cache_top_, cell, level, th_.pad_radius, stamp_number_, stamped_);
  have_stamp_ = true;
  stamp_body_ = s.body;
  stamp_top_ = cache_top_;
  stamp_level_ = level;
  keep_path_point({s.body, piece_, s.u, s.v, cache_top_, exam_.coverage[b].visits(cell) >= 2});
}

// One stamp in path_stride_ joins the path; a full path drops every other point and
// doubles the stride. Points stay in order, each with its own piece.
void SamplePass::keep_path_point(const PathPoint& p) {
  if (stamps_seen_++ % path_stride_ != 0) return;
  if (path.size() == kMaxPathPoints) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < path.size(); k += 2) path[kept++] = path[k];
    path.resize(kept);
    path_stride_ *= 2;
    if ((stamps_seen_ - 1) % path_stride_ != 0) return;
  }
  path.push_back(p);
}

// Dwell and peak force since the last stamp go to the cells it covered.
void SamplePass::flush() {
  if (have_stamp_ && pending_dwell_ > 0.0)
    exam_.coverage[static_cast<std::size_t>(stamp_body_)].add_dwell(stamped_, pending_dwell_, pending_peak_);
  pending_dwell_ = pending_peak_ = 0.0;
}

}  // namespace palpa::score::detail
