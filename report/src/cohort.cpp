#include "palpa/report/cohort.hpp"

#include <fmt/format.h>

#include "palpa/report/encoding.hpp"
#include "palpa/report/session_html.hpp"

namespace palpa::report {

std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const CusumDesign& design) {
  std::size_t sessions = 0;
  for (const auto& t : trainees) sessions += t.attempts.size();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<title>Palpa cohort report</title>\n<style>\n" + report_css() + "</style>\n</head>\n<body>\n";
  html += fmt::format(
      "<h1>Cohort report</h1>\n<p class=\"meta\">{} sessions scored, {} trainees, {} files skipped.</p>\n", sessions,
      trainees.size(), skipped.size());
  html += "<h2>Trainees</h2>\n<table>\n<tr><th>trainee</th><th>sessions</th><th>pass rate</th><th>mean score</th>"
          "<th>last score</th><th>CUSUM verdict</th></tr>\n";
  for (const auto& t : trainees) {
    std::size_t passed = 0;
    double sum = 0.0;
    for (const auto& a : t.attempts) {
      passed += a.passed ? 1 : 0;
      sum += a.score;
    }
    const double n = static_cast<double>(t.attempts.size());
    const auto verdict = to_string(t.cusum.verdict, "undecided");
    const char* cls = t.cusum.verdict == CusumSignal::Acceptable     ? " class=\"ok\""
                      : t.cusum.verdict == CusumSignal::Unacceptable ? " class=\"bad\""
                                                                     : "";
    const std::string pass_rate = n > 0 ? fmt::format("{:.0f} %", 100.0 * static_cast<double>(passed) / n) : "-";
    const std::string mean = n > 0 ? fmt::format("{:.1f}", 100.0 * sum / n) : "-";
    const std::string last = n > 0 ? fmt::format("{:.1f}", 100.0 * t.attempts.back().score) : "-";
    html += fmt::format("<tr><td><a href=\"#t-{}\">{}</a></td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                        "<td class=\"num\">{}</td><td class=\"num\">{}</td><td{}>{}</td></tr>\n",
                        html_escape(t.file_stem), html_escape(t.trainee), t.attempts.size(), pass_rate, mean, last,
                        cls, verdict);
  }
  html += fmt::format(
      "</table>\n<p>Scores are out of 100. CUSUM of failures after Bolsin &amp; Colson (2000): acceptable "
      "failure rate p0 = {:.2f}, unacceptable p1 = {:.2f}, alpha = {:.2f}, beta = {:.2f}; each pass subtracts "
      "s = {:.4f}, each failure adds 1 - s; a fall of h0 = {:.4f} signals an acceptable failure rate, a rise of "
      "h1 = {:.4f} an unacceptable one (each signal restarts the test).</p>\n",
      design.p0, design.p1, design.alpha, design.beta, design.s(), design.h0(), design.h1());
  for (const auto& t : trainees) {
    html += "<h2 id=\"t-" + html_escape(t.file_stem) + "\">" + html_escape(t.trainee) + "</h2>\n";
    html += png_img(t.png, "learning curve of " + t.trainee) + "\n";
  }
  html += "<h2>Skipped files</h2>\n";
  if (skipped.empty()) {
    html += "<p>None.</p>\n";
  } else {
    html += "<table>\n<tr><th>file</th><th>error</th></tr>\n";
    for (const auto& s : skipped)
      html += "<tr><td>" + html_escape(s.file) + "</td><td>" + html_escape(s.error) + "</td></tr>\n";
    html += "</table>\n";
  }
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace palpa::report
