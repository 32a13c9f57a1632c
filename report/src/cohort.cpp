#include "palpa/report/cohort.hpp"

#include <cstdio>

#include "palpa/report/encoding.hpp"
#include "palpa/report/session_html.hpp"

namespace palpa::report {
namespace {
std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}
}  // namespace

std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const CusumDesign& design) {
  std::size_t sessions = 0;
  for (const auto& t : trainees) sessions += t.attempts.size();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<title>Palpa cohort report</title>\n<style>\n" + report_css() + "</style>\n</head>\n<body>\n";
  html += "<h1>Cohort report</h1>\n<p class=\"meta\">" + std::to_string(sessions) + " sessions scored, " +
          std::to_string(trainees.size()) + " trainees, " + std::to_string(skipped.size()) + " files skipped.</p>\n";
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
    html += "<tr><td><a href=\"#t-" + html_escape(t.file_stem) + "\">" + html_escape(t.trainee) + "</a></td>" +
            "<td class=\"num\">" + std::to_string(t.attempts.size()) + "</td><td class=\"num\">" +
            (n > 0 ? fixed(100.0 * static_cast<double>(passed) / n, 0) + " %" : "-") + "</td><td class=\"num\">" +
            (n > 0 ? fixed(100.0 * sum / n, 1) : "-") + "</td><td class=\"num\">" +
            (n > 0 ? fixed(100.0 * t.attempts.back().score, 1) : "-") + "</td><td" + cls + ">" +
            std::string(verdict) + "</td></tr>\n";
  }
  html += "</table>\n<p>Scores are out of 100. CUSUM of failures after Bolsin &amp; Colson (2000): acceptable "
          "failure rate p0 = " + fixed(design.p0, 2) + ", unacceptable p1 = " + fixed(design.p1, 2) +
          ", alpha = " + fixed(design.alpha, 2) + ", beta = " + fixed(design.beta, 2) + "; each pass subtracts s = " +
          fixed(design.s(), 4) + ", each failure adds 1 - s; a fall of h0 = " + fixed(design.h0(), 4) +
          " signals an acceptable failure rate, a rise of h1 = " + fixed(design.h1(), 4) +
          " an unacceptable one (each signal restarts the test).</p>\n";
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
