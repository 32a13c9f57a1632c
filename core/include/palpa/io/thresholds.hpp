#pragma once
// What a session is scored against: pass/fail gates, cut points and sub-score weights, with
// defaults from the palpation literature (docs/scoring.md gives each default's source).
// A case may override any of them in its optional "scoring" object and restrict the exam
// region with "exam_region" (docs/case-format.md). They are part of the case file, so they
// live here with it: parse_case checks them, and score (a layer above) scores with them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/io/case_file.hpp"

namespace palpa::io {

/// A rectangle of one body's (u, v) parameter square; the exam region is their union.
struct RegionPart {
  std::string body;  ///< body id
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
};

struct Thresholds {
  // Marks and tumours
  double hit_margin = 0.010;           ///< m: a mark hits a tumour within radius + this
  double detectable_diameter = 0.003;  ///< m: smaller tumours do not count for the sensitivity gate
  int max_false_positives = 1;         ///< gate
  // Coverage of the exam region (top contour, area-weighted)
  double pad_radius = 0.0075;          ///< m: a fingertip contact covers this radius around it
  double min_coverage = 0.90;          ///< gate
  double min_deep_coverage = 0.80;     ///< gate
  double expert_coverage = 0.95;       ///< full sub-score from here
  // Pressure levels by indentation over the local tissue thickness (2 R)
  double light_max = 0.20;             ///< depth / thickness below this: light
  double deep_min = 0.50;              ///< at or above this: deep; in between: medium
  // Force
  double max_force = 20.0;             ///< N: safety gate on the peak force
  double palpate_radius = 0.010;       ///< m: contacts this close to a mark count as palpating it
  double palpate_ratio_low = 1.1;      ///< target band of the palpate/search force ratio
  double palpate_ratio_high = 1.3;
  // Search pattern and duration
  double strip_spacing = 0.015;        ///< m: one finger pad
  double min_duration = 60.0;          ///< s: shorter exams are flagged (not a gate)
  // Weights of the sub-scores in the overall score (normalized when used)
  double weight_sensitivity = 0.35;
  double weight_false_positives = 0.15;
  double weight_localization = 0.10;
  double weight_coverage = 0.20;
  double weight_deep_coverage = 0.10;
  double weight_pattern = 0.05;
  double weight_pressure = 0.05;
  /// Empty: the whole top contour of every body.
  std::vector<RegionPart> exam_region;
};

/// The thresholds a case asks for: defaults overridden by its "scoring" object and its
/// "exam_region". Problems (unknown key, wrong type, out of range, unknown body, empty
/// rectangle, light_max >= deep_min) are appended with JSON pointers such as
/// /scoring/min_coverage; the returned thresholds then hold the defaults for those fields.
Thresholds thresholds_from_case(const nlohmann::json& case_document, std::vector<Problem>& problems);

/// The effective thresholds as a JSON object with the "scoring" keys (for reports).
nlohmann::json to_json(const Thresholds& thresholds);

}  // namespace palpa::io
