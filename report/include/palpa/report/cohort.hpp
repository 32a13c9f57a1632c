#pragma once
// The cohort page of a batch: which sessions it covers and which the learning curves leave
// out (with the option that includes them), one row per trainee (sessions, pass rate, mean
// and last score out of 100, the proficiency verdict in words, the CUSUM's last signal in
// words), per-case and per-station summaries, each trainee's curve per case, the rule and
// the chart explained, each trainee's learning-curve image inline, links to the session
// reports (--reports), and the session files that were skipped with their errors. Text
// from session files (trainee ids, case titles, stations, file names) is shown escaped
// (printable.hpp) and shortened to 60 characters, the whole value in the title attribute.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "palpa/report/cohort_tables.hpp"
#include "palpa/report/learning_curve.hpp"

namespace palpa::report {

struct TraineeCurve {
  std::string trainee;
  std::string file_stem;           ///< trainee_file_stem(trainee)
  std::vector<Attempt> attempts;   ///< in started_at order
  Cusum cusum;
  Proficiency proficiency;
  std::vector<std::uint8_t> png;   ///< learning_curve_plot as PNG
  std::string case_id;             ///< a curve of one case: its case_id; empty: every case
  std::string case_name;           ///< case_name of its first attempt
  std::string files;               ///< its CSV and PNG relative to the page, without extension
};

/// A scored session whose report page was written (--reports).
struct SessionLink {
  std::string trainee;
  std::string started_at;
  std::string outcome;   ///< outcome_of: passed, failed, abandoned, incomplete
  std::string href;      ///< relative to the page: "sessions/STEM.html", STEM percent-encoded
};

struct SkippedFile {
  std::string file;
  std::string error;  ///< the one-line error
};

struct CohortPage {
  std::vector<TraineeCurve> trainees;     ///< one curve per trainee over every case
  std::vector<TraineeCurve> case_curves;  ///< one curve per trainee and case
  std::vector<GroupSummary> cases, stations;
  std::vector<SessionLink> sessions;      ///< by trainee then start; empty without --reports
  std::vector<SkippedFile> skipped;
  std::string selection;                  ///< as below
  std::vector<std::string> notes;         ///< left_out_notes: what the curves leave out and why
};

std::string cohort_html(const CohortPage& page, const CusumDesign& design = {}, const ProficiencyRule& rule = {});

/// The href of a file under `folder` named STEM + `extension`, STEM percent-encoded except
/// letters, digits, '.', '_' and '-': "sessions/bob%20one.html".
std::string relative_href(std::string_view folder, std::string_view stem, std::string_view extension);

/// `selection` says which sessions the page covers, in words ("sessions from 2026-11-01 to
/// 2026-11-30, case default"); empty: every session given.
std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const std::string& selection = {}, const CusumDesign& design = {},
                        const ProficiencyRule& rule = {});

}  // namespace palpa::report
