#include "palpa/report/cohort.hpp"

#include <fmt/format.h>

#include "palpa/report/encoding.hpp"
#include "palpa/report/session_html.hpp"

namespace palpa::report {
namespace {

std::string trainee_row(const TraineeCurve& t, const CusumDesign& design) {
  std::size_t passed = 0;
  double sum = 0.0;
  for (const auto& a : t.attempts) {
    passed += a.passed ? 1 : 0;
    sum += a.score;
  }
  const double n = static_cast<double>(t.attempts.size());
  const char* cls = t.proficiency.now() ? " class=\"ok\"" : "";
  const std::string pass_rate = n > 0 ? fmt::format("{} of {}", passed, t.attempts.size()) : "-";
  const std::string mean = n > 0 ? fmt::format("{:.1f}", 100.0 * sum / n) : "-";
  const std::string last = n > 0 ? fmt::format("{:.1f}", 100.0 * t.attempts.back().score) : "-";
  return fmt::format("<tr><td><a href=\"#t-{}\">{}</a></td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                     "<td class=\"num\">{}</td><td class=\"num\">{}</td><td{}>{}</td><td>{}</td></tr>\n",
                     html_escape(t.file_stem), html_escape(t.trainee), t.attempts.size(), pass_rate, mean, last, cls,
                     html_escape(t.proficiency.headline()), html_escape(cusum_words(t.cusum, design)));
}

std::string method_text(const CusumDesign& design, const ProficiencyRule& rule) {
  return fmt::format(
      "<p>Scores are out of 100. <strong>Verdict</strong>: a trainee is proficient once her last {0} attempts "
      "passed, {0} in a row, whatever came before; a later failure ends it and {0} new passes in a row regain "
      "it (proficiency-based training: Ritter &amp; Scott 2007). The verdict follows the latest attempts: "
      "\"proficient since attempt 7\", \"not yet: 2 of the last {1} passed\".</p>\n"
      "<p><strong>CUSUM of failures</strong> (Bolsin &amp; Colson 2000), the lower plot, as supporting evidence "
      "on the failure rate: {2}</p>\n",
      rule.consecutive, rule.window, html_escape(cusum_caption(design)));
}

std::string skipped_section(const std::vector<SkippedFile>& skipped) {
  std::string html = "<h2>Skipped files</h2>\n";
  if (skipped.empty()) return html + "<p>None.</p>\n";
  html += "<table>\n<tr><th>file</th><th>error</th></tr>\n";
  for (const auto& s : skipped)
    html += "<tr><td>" + html_escape(s.file) + "</td><td>" + html_escape(s.error) + "</td></tr>\n";
  return html + "</table>\n";
}

}  // namespace

std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const std::string& selection, const CusumDesign& design, const ProficiencyRule& rule) {
  std::size_t sessions = 0;
  for (const auto& t : trainees) sessions += t.attempts.size();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<title>Palpa cohort report</title>\n<style>\n" + report_css() + "</style>\n</head>\n<body>\n";
  html += fmt::format("<h1>Cohort report</h1>\n<p class=\"meta\">Covers {}. {} sessions in the learning curves, {} trainee(s), "
                      "{} files skipped.</p>\n",
                      html_escape(selection.empty() ? std::string("every session given") : selection), sessions,
                      trainees.size(), skipped.size());
  html += "<h2>Trainees</h2>\n<table>\n<tr><th>trainee</th><th>sessions</th><th>passed</th><th>mean score</th>"
          "<th>last score</th><th>verdict</th><th>CUSUM</th></tr>\n";
  for (const auto& t : trainees) html += trainee_row(t, design);
  html += "</table>\n" + method_text(design, rule);
  for (const auto& t : trainees) {
    html += "<h2 id=\"t-" + html_escape(t.file_stem) + "\">" + html_escape(t.trainee) + ": " +
            html_escape(t.proficiency.headline()) + "</h2>\n";
    html += png_img(t.png, "learning curve of " + t.trainee) + "\n";
  }
  html += skipped_section(skipped);
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace palpa::report
