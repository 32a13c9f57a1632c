#include "palpa/report/summary_csv.hpp"

#include <limits>

#include <fmt/format.h>

#include "palpa/report/csv_number.hpp"
#include "palpa/report/encoding.hpp"
#include "palpa/report/printable.hpp"

namespace palpa::report {

const std::string& csv_header() {
  static const std::string kHeader =
      "file,session_id,trainee,case,started_at,passed,score,sensitivity,false_positives,"
      "localization_error_mm,coverage,deep_coverage,duration_s,contact_time_s,peak_force_n,"
      "safe,palpate_search_ratio,pattern,light_s,medium_s,deep_s,complete,samples,"
      "outcome,mode,case_file,case_id,score_100,station";
  return kHeader;
}

std::string csv_text(std::string_view text) {
  if (is_printable(text)) return csv_field(text);
  return csv_field(printable(text, std::numeric_limits<std::size_t>::max()));
}

double mean_localization_error_mm(const score::Score& score) {
  if (score.localization_error_mm.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const double e : score.localization_error_mm) sum += e;
  return sum / static_cast<double>(score.localization_error_mm.size());
}

const char* outcome_of(const score::Score& s) {
  if (s.abandoned) return "abandoned";
  if (!s.complete) return "incomplete";
  return s.passed ? "passed" : "failed";
}

std::string csv_row(const SessionHeader& h, const score::Score& s) {
  std::string row;
  bool first = true;  // every field but the first follows a comma, even after an empty one
  auto text = [&row, &first](std::string_view v) {
    if (!first) row += ',';
    first = false;
    row += csv_text(v);
  };
  auto number = [&row](double v, CsvUnit unit) {
    row += ',';
    row += csv_number(v, unit);
  };
  auto flag = [&row](bool v) { row += v ? ",1" : ",0"; };
  auto count = [&row](auto n) { row += fmt::format(",{}", n); };
  text(h.file);
  text(h.id);
  text(h.trainee);
  text(h.case_title);
  text(h.started_at);
  flag(s.passed);
  number(s.score, CsvUnit::Fraction);
  number(s.sensitivity, CsvUnit::Fraction);
  count(s.false_positives);
  number(mean_localization_error_mm(s), CsvUnit::Millimetre);
  number(s.coverage, CsvUnit::Fraction);
  number(s.deep_coverage, CsvUnit::Fraction);
  number(s.duration_s, CsvUnit::Second);
  number(s.contact_time_s, CsvUnit::Second);
  number(s.peak_force_n, CsvUnit::Newton);
  flag(s.safe);
  number(s.palpate_search_ratio, CsvUnit::Ratio);
  text(score::to_string(s.pattern.kind));
  number(s.pressure.light_s, CsvUnit::Second);
  number(s.pressure.medium_s, CsvUnit::Second);
  number(s.pressure.deep_s, CsvUnit::Second);
  flag(s.complete);
  count(s.samples);
  text(outcome_of(s));
  text(h.mode);
  text(h.case_file);
  text(h.case_id);
  number(100.0 * s.score, CsvUnit::Score100);
  text(h.station);
  return row;
}

}  // namespace palpa::report
