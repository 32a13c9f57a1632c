#pragma once
// One number, one rounding: every gate figure (coverage, deep coverage, peak force,
// localization error) is shown the same way on the score card, by palpa-cli score, in the
// HTML report and in review, and the gates judge the figure people see
// (docs/scoring.md, "Rounding"). Files (JSON, CSV) keep the unrounded measures.
#include <string>

namespace palpa::score {

struct Gate;

/// A share (0..1) as the percent shown: one decimal, rounded down (79.96 % of an area is
/// not the 80 % a gate needs and must not read as if it were): 0.8995 -> 89.9.
double shown_percent(double share);
/// "89.9%" (shown_percent with one decimal and a percent sign).
std::string percent_text(double share);
/// A force (N) as shown: one decimal, rounded up (a peak never reads below what was
/// pressed): 20.01 -> 20.1.
double shown_force_n(double newtons);
/// "20.1 N".
std::string force_text(double newtons);
/// A distance in mm as shown: one decimal, rounded to the nearest: "3.2 mm".
std::string mm_text(double mm);
/// A gate's measured value as shown (coverage "89.9%", safety "20.1 N", false positives
/// "2", sensitivity "50.0%").
std::string gate_value_text(const Gate& gate);
/// A gate's threshold as shown, in the same unit as gate_value_text.
std::string gate_threshold_text(const Gate& gate);

}  // namespace palpa::score
