// The push-back trace and the pseudo-haptic finger (stroke_trace.hpp, docs/perception.md).
#include "palpa/live/stroke_trace.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::live {

namespace {
constexpr double kSpotSpacing = 0.0005;    // m between the baseline's samples along the skin
constexpr std::size_t kMaxPoints = 4096;   // a stroke's points, at most (a minute at 60 Hz)
constexpr double kRestBeforeCatchUp = 0.1; // s the pointer rests before the finger catches up
}  // namespace

void StrokeTrace::restart() {
  points_.clear();
  spots_.clear();
  along_ = 0.0;
  ++stroke_;
}

void StrokeTrace::feed(double t, const Vec3& finger, double firmness, double setting, const Vec3& skin) {
  if (!(firmness > 0.0) || !std::isfinite(firmness) || !finger.allFinite()) {
    on_ = false;
    points_.clear();
    spots_.clear();
    return;
  }
  const bool jumped = !points_.empty() && (finger - points_.back().at).norm() > kJump;
  if (!on_ || setting != setting_ || jumped) restart();
  else along_ += (finger - points_.back().at).norm();
  on_ = true;
  setting_ = setting;
  if (spots_.empty() || along_ - spots_.back().along >= kSpotSpacing) spots_.push_back({along_, firmness});
  while (along_ - spots_.front().along > kBaselineSpan) spots_.pop_front();
  points_.push_back({t, along_, firmness, baseline(), finger, skin});
  while (points_.size() > kMaxPoints || t - points_.front().t > kMemory) points_.pop_front();
}

double StrokeTrace::baseline() const {
  // The median: a lump under part of the span does not lift it (at most 121 values).
  auto& values = scratch_;
  values.clear();
  for (const auto& s : spots_) values.push_back(s.firmness);
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

double StrokeTrace::contrast() const {
  if (points_.empty() || along_ < kSettledAlong || !(points_.back().baseline > 0.0)) return 1.0;
  return points_.back().firmness / points_.back().baseline;
}

double control_display_gain(double contrast) {
  if (!(contrast > 1.0) || !std::isfinite(contrast)) return 1.0;
  return std::max(kMinGain, std::pow(1.0 / contrast, kGainPower));
}

void ControlDisplay::reset(const Eigen::Vector2d& at) {
  pointer_ = at;
  finger_ = at;
  rest_ = 0.0;
  started_ = true;
}

Eigen::Vector2d ControlDisplay::follow(const Eigen::Vector2d& pointer, double gain, double dt) {
  if (!started_ || !pointer.allFinite()) {
    reset(pointer.allFinite() ? pointer : finger_);
    return finger_;
  }
  const Eigen::Vector2d move = pointer - pointer_;
  const double g = std::isfinite(gain) ? std::clamp(gain, 0.0, 1.0) : 1.0;
  dt = std::isfinite(dt) ? std::max(0.0, dt) : 0.0;
  rest_ = move.squaredNorm() > 0.0 ? 0.0 : rest_ + dt;
  finger_ += g * move;
  // Plain tissue again, or the pointer at rest: the finger catches up with the pointer.
  if (g >= 1.0 || rest_ >= kRestBeforeCatchUp) finger_ += (pointer - finger_) * (1.0 - std::exp(-dt / kCatchUp));
  const Eigen::Vector2d lag = pointer - finger_;
  if (lag.norm() > kMaxLag) finger_ = pointer - lag * (kMaxLag / lag.norm());
  pointer_ = pointer;
  return finger_;
}

}  // namespace palpa::live
