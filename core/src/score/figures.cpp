#include "palpa/score/figures.hpp"

#include <cmath>

#include <fmt/format.h>

#include "palpa/score/score.hpp"

namespace palpa::score {
namespace {

// Binary fractions: 0.9 is 0.89999..., 100 * 0.9 * 10 lands a hair under 900; the guard
// keeps such figures at their decimal value without moving a real 899.99 up.
constexpr double kGuard = 1e-6;

std::string one_decimal(double v) {
  std::string s = fmt::format("{:.1f}", v);
  if (s == "-0.0") s = "0.0";
  return s;
}

std::string text_of(const std::string& name, double v) {
  if (name == "safety") return force_text(v);
  if (name == "false_positives") return fmt::format("{:.0f}", v);
  return percent_text(v);
}

}  // namespace

double shown_percent(double share) {
  if (!std::isfinite(share)) return share;
  return std::floor(1000.0 * share + kGuard) / 10.0;
}

std::string percent_text(double share) {
  if (!std::isfinite(share)) return "-";
  return one_decimal(shown_percent(share)) + "%";
}

double shown_force_n(double newtons) {
  if (!std::isfinite(newtons)) return newtons;
  return std::ceil(10.0 * newtons - kGuard) / 10.0;
}

std::string force_text(double newtons) {
  if (!std::isfinite(newtons)) return "-";
  return one_decimal(shown_force_n(newtons)) + " N";
}

std::string mm_text(double mm) {
  if (!std::isfinite(mm)) return "-";
  return one_decimal(std::round(10.0 * mm) / 10.0) + " mm";
}

std::string gate_value_text(const Gate& gate) { return text_of(gate.name, gate.value); }

std::string gate_threshold_text(const Gate& gate) { return text_of(gate.name, gate.threshold); }

}  // namespace palpa::score
