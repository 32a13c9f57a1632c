#include "verdict.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "../common/numeric.hpp"
#include "palpa/score/figures.hpp"

namespace palpa::score::detail {
namespace {

// Sub-score bounds (docs/scoring.md, "Sub-scores").
// Coverage earns nothing up to half the region: below it no search was made.
constexpr double kCoverageFloor = 0.5;
// A pressure level earns its full third once it takes this share of the contact time
// (MammaCare's light, medium and deep each used, not only one of them).
constexpr double kLevelShareForFullCredit = 0.10;
// The pattern sub-score by class: a systematic strip search is what training teaches.
constexpr double kPatternEfficient = 1.0, kPatternThorough = 0.75, kPatternOther = 0.25, kPatternNone = 0.0;
// Strips more than this many finger pads apart leave ground between them untouched.
constexpr double kWideStripFactor = 1.25;

// A gate judges the figure shown (figures.hpp): 89.96 % reads 89.9 % and fails a 90 % gate.
bool at_least(double share, double needed) { return shown_percent(share) >= shown_percent(needed); }

std::string tumour_text(const TumourResult& t, double depth_m) {
  return fmt::format("the {:.0f} mm mass {:.0f} mm deep at ({:.0f}, {:.0f}, {:.0f}) mm in {}", 2000.0 * t.radius,
                     1000.0 * depth_m, 1000.0 * t.center[0], 1000.0 * t.center[1], 1000.0 * t.center[2], t.body);
}

Gate sensitivity_gate(const Score& out, const std::vector<double>& tumour_depth) {
  int detectable = 0, found = 0;
  std::string missed;
  for (std::size_t k = 0; k < out.tumours.size(); ++k) {
    const TumourResult& t = out.tumours[k];
    if (!t.detectable) continue;
    ++detectable;
    if (t.found) {
      ++found;
      continue;
    }
    missed += missed.empty() ? ": " : "; ";
    missed += tumour_text(t, tumour_depth[k]);
  }
  Gate g{"sensitivity", found == detectable, out.sensitivity, 1.0, fmt::format("Found {} of {} tumours", found, detectable)};
  g.message += missed.empty() ? "." : missed + (detectable - found == 1 ? " was missed." : " were missed.");
  return g;
}

double localization_of(const Score& out, const Thresholds& th) {
  if (out.localization_error_mm.empty()) return out.tumours.empty() ? 1.0 : 0.0;
  double sum = 0.0;
  for (const auto& t : out.tumours)
    if (t.found) sum += clamp01(1.0 - t.localization_error_mm / (1000.0 * (t.radius + th.hit_margin)));
  return sum / double(out.localization_error_mm.size());
}

double pressure_of(const Score& out) {
  if (!(out.contact_time_s > 0.0)) return 0.0;
  double pressure = 0.0;
  for (double level_s : {out.pressure.light_s, out.pressure.medium_s, out.pressure.deep_s})
    pressure += clamp01(level_s / out.contact_time_s / kLevelShareForFullCredit) / 3.0;
  return pressure;
}

double pattern_of(PatternKind kind) {
  switch (kind) {
    case PatternKind::Efficient: return kPatternEfficient;
    case PatternKind::Thorough: return kPatternThorough;
    case PatternKind::None: return kPatternNone;
    case PatternKind::Sporadic:
    case PatternKind::Localized: break;
  }
  return kPatternOther;
}

void add_tumour_and_mark_notes(Score& out, const Thresholds& th) {
  for (std::size_t k = 0; k < out.tumours.size(); ++k) {
    if (out.tumours[k].detectable) continue;
    out.notes.push_back(fmt::format(
        "tumour {} ({:.1f} mm across) is smaller than the detectable size ({:.1f} mm): it does not count for the "
        "sensitivity gate",
        k + 1, 2000.0 * out.tumours[k].radius, 1000.0 * th.detectable_diameter));
  }
  for (const auto& m : out.marks) {
    if (m.duplicate) out.notes.push_back(fmt::format("mark {} marks a tumour already found (duplicate)", m.id));
  }
}

void add_technique_notes(Score& out, const Thresholds& th) {
  const double ratio = out.palpate_search_ratio;
  if (ratio > 0.0 && (ratio < th.palpate_ratio_low || ratio > th.palpate_ratio_high)) {
    out.notes.push_back(fmt::format("palpate/search force ratio {:.2f} is outside the expert band {:.2f}-{:.2f}", ratio,
                                    th.palpate_ratio_low, th.palpate_ratio_high));
  }
  if (out.pattern.strip_spacing_mm > kWideStripFactor * 1000.0 * th.strip_spacing) {
    out.notes.push_back(fmt::format("strips {:.0f} mm apart: wider than one finger pad ({:.0f} mm)",
                                    out.pattern.strip_spacing_mm, 1000.0 * th.strip_spacing));
  }
}

}  // namespace

std::vector<Gate> gates_of(const Score& out, const std::vector<double>& tumour_depth, const Thresholds& th) {
  std::vector<Gate> gates;
  gates.push_back(sensitivity_gate(out, tumour_depth));
  gates.push_back({"false_positives", out.false_positives <= th.max_false_positives, double(out.false_positives),
                   double(th.max_false_positives),
                   fmt::format("{} {} matched no tumour (at most {} allowed).", out.false_positives,
                               out.false_positives == 1 ? "mark" : "marks", th.max_false_positives)});
  gates.push_back({"coverage", at_least(out.coverage, th.min_coverage), out.coverage, th.min_coverage,
                   fmt::format("Covered {} of the exam region ({} needed).", percent_text(out.coverage),
                               percent_text(th.min_coverage))});
  gates.push_back({"deep_coverage", at_least(out.deep_coverage, th.min_deep_coverage), out.deep_coverage,
                   th.min_deep_coverage,
                   fmt::format("Pressed deep over {} of the exam region ({} needed).", percent_text(out.deep_coverage),
                               percent_text(th.min_deep_coverage))});
  gates.push_back({"safety", out.safe, out.peak_force_n, th.max_force,
                   out.safe ? fmt::format("Peak force {} (limit {}).", force_text(out.peak_force_n),
                                          force_text(th.max_force))
                            : fmt::format("Peak force {} is above the {} limit.", force_text(out.peak_force_n),
                                          force_text(th.max_force))});
  return gates;
}

std::vector<SubScore> subscores_of(const Score& out, const Thresholds& th) {
  // False positives cost a share each, down to 0 at twice the allowed number plus 2.
  const double fp_zero = 2.0 * th.max_false_positives + 2.0;
  std::vector<SubScore> subscores = {
      {"sensitivity", out.sensitivity, th.weight_sensitivity},
      {"false_positives", clamp01(1.0 - out.false_positives / fp_zero), th.weight_false_positives},
      {"localization", localization_of(out, th), th.weight_localization},
      {"coverage", clamp01((out.coverage - kCoverageFloor) / (th.expert_coverage - kCoverageFloor)),
       th.weight_coverage},
      {"deep_coverage", th.min_deep_coverage > 0.0 ? clamp01(out.deep_coverage / th.min_deep_coverage) : 1.0,
       th.weight_deep_coverage},
      {"pattern", pattern_of(out.pattern.kind), th.weight_pattern},
      {"pressure", pressure_of(out), th.weight_pressure},
  };
  double weight_sum = 0.0;
  for (const auto& s : subscores) weight_sum += s.weight;
  for (auto& s : subscores) s.weight = weight_sum > 0.0 ? s.weight / weight_sum : 0.0;
  return subscores;
}

void add_notes(Score& out, bool complete, std::optional<double> last_t, const Timeline& tl, std::size_t ignored,
               const Thresholds& th) {
  if (out.abandoned) out.notes.push_back("abandoned by the trainee: not an exam, left out of learning curves");
  if (!complete) {
    out.notes.push_back(
        fmt::format("session incomplete (no end event): scored up to t = {:.1f} s", last_t.value_or(tl.end)));
  }
  if (!last_t) out.notes.push_back("no samples recorded");
  if (out.short_exam) {
    out.notes.push_back(fmt::format("short exam: {:.0f} s of active time (at least {:.0f} s expected)", out.duration_s,
                                    th.min_duration));
  }
  add_tumour_and_mark_notes(out, th);
  add_technique_notes(out, th);
  if (ignored > 0) out.notes.push_back(fmt::format("{} samples name a body the case does not have: ignored", ignored));
}

}  // namespace palpa::score::detail
