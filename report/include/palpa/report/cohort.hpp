#pragma once
// The cohort page of a batch: which sessions it covers, one row per trainee (sessions, pass
// rate, mean and last score out of 100, the proficiency verdict in words, the CUSUM's last
// signal in words), the rule and the chart explained, each trainee's learning-curve image
// inline, and the session files that were skipped with their errors.
#include <cstdint>
#include <string>
#include <vector>

#include "palpa/report/learning_curve.hpp"

namespace palpa::report {

struct TraineeCurve {
  std::string trainee;
  std::string file_stem;           ///< trainee_file_stem(trainee)
  std::vector<Attempt> attempts;   ///< in started_at order
  Cusum cusum;
  Proficiency proficiency;
  std::vector<std::uint8_t> png;   ///< learning_curve_plot as PNG
};

struct SkippedFile {
  std::string file;
  std::string error;  ///< the one-line error
};

/// `selection` says which sessions the page covers, in words ("sessions from 2026-11-01 to
/// 2026-11-30, case default"); empty: every session given.
std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const std::string& selection = {}, const CusumDesign& design = {},
                        const ProficiencyRule& rule = {});

}  // namespace palpa::report
