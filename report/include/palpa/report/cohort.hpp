#pragma once
// The cohort page of a batch: one row per trainee (sessions, pass rate, mean and last
// score, CUSUM verdict), each trainee's learning-curve image inline, and the session files
// that were skipped with their errors.
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
  std::vector<std::uint8_t> png;   ///< learning_curve_plot as PNG
};

struct SkippedFile {
  std::string file;
  std::string error;  ///< the one-line error
};

std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const CusumDesign& design = {});

}  // namespace palpa::report
