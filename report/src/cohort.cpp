#include "palpa/report/cohort.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "palpa/report/encoding.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/report/session_html.hpp"

namespace palpa::report {
namespace {

// Long names wrap inside their cell instead of pushing the table off the page.
constexpr const char* kCohortCss =
    "td,th{overflow-wrap:anywhere;max-width:22em}h2,p{overflow-wrap:anywhere}td.links a{margin-right:.6em}\n";

constexpr std::size_t kShownChars = 60;
// Errors are ours around a file name: shortened only when absurdly long, so they stay readable.
constexpr std::size_t kShownErrorChars = 400;

// Untrusted text for the page: controls and bidi overrides escaped, at most 60 characters
// shown with "…"; the whole (escaped) value in a title when anything was changed. Plain
// short text is written as html_escape alone, as before.
std::string shown(std::string_view text, std::size_t max_chars = kShownChars) {
  const std::string brief = printable(text, max_chars);
  if (brief == text) return html_escape(text);
  return "<span title=\"" + html_escape(printable(text, std::numeric_limits<std::size_t>::max())) + "\">" +
         html_escape(brief) + "</span>";
}

std::string score_100(double v) { return std::isnan(v) ? "-" : fmt::format("{:.1f}", v); }

std::string curve_cells(const TraineeCurve& t, const CusumDesign& design) {
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
  return fmt::format("<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                     "<td class=\"num\">{}</td><td{}>{}</td><td>{}</td>",
                     t.attempts.size(), pass_rate, mean, last, cls, html_escape(t.proficiency.headline()),
                     html_escape(cusum_words(t.cusum, design)));
}

std::string trainee_row(const TraineeCurve& t, const CusumDesign& design) {
  return fmt::format("<tr><td><a href=\"#t-{}\">{}</a></td>{}</tr>\n", html_escape(t.file_stem), shown(t.trainee),
                     curve_cells(t, design));
}

std::string case_curves_section(const std::vector<TraineeCurve>& curves, const CusumDesign& design) {
  if (curves.empty()) return {};
  std::string html =
      "<h2>Learning curves per case</h2>\n<p>Each trainee's attempts at one case, so that cases of different "
      "difficulty are not mixed; CSV and plot under curves/TRAINEE/CASE.</p>\n<table>\n<tr><th>trainee</th>"
      "<th>case</th><th>sessions</th><th>passed</th><th>mean score</th><th>last score</th><th>verdict</th>"
      "<th>CUSUM</th><th>files</th></tr>\n";
  for (const auto& t : curves) {
    html += fmt::format("<tr><td>{}</td><td>{}</td>{}<td class=\"links\"><a href=\"{}.png\">plot</a>"
                        "<a href=\"{}.csv\">CSV</a></td></tr>\n",
                        shown(t.trainee), shown(t.case_name), curve_cells(t, design), html_escape(t.files),
                        html_escape(t.files));
  }
  return html + "</table>\n";
}

std::string group_table(const char* title, const char* key_heading, const std::vector<GroupSummary>& rows,
                        const char* empty_key) {
  std::string html = fmt::format(
      "<h2>{}</h2>\n<table>\n<tr><th>{}</th><th>sessions</th><th>scored</th><th>passed</th><th>pass rate</th>"
      "<th>median score</th><th>trainees</th><th>proficient trainees</th></tr>\n",
      title, key_heading);
  for (const auto& g : rows) {
    const std::string rate = g.scored > 0 ? fmt::format("{:.0f} %", 100.0 * static_cast<double>(g.passed) /
                                                                        static_cast<double>(g.scored))
                                          : "-";
    const std::string key = g.key.empty() ? std::string(empty_key) : shown(g.name.empty() ? g.key : g.name);
    html += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                        "<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
                        "<td class=\"num\">{}</td></tr>\n",
                        key, g.sessions, g.scored, g.passed, rate, score_100(g.median_score_100), g.trainees,
                        g.proficient_trainees);
  }
  return html + "</table>\n";
}

std::string summaries_section(const CohortPage& page) {
  if (page.cases.empty() && page.stations.empty()) return {};
  return group_table("Cases", "case", page.cases, "(no case id)") +
         group_table("Stations", "station", page.stations, "(not recorded)") +
         "<p>Every scored session counts here, whatever its mode (as in summary.csv and cases.csv, "
         "stations.csv); the pass rate and median score leave out abandoned attempts (no exam); a trainee is "
         "proficient when her learning curve of a case done here says so now.</p>\n";
}

// With --reports: each trainee's sessions, in start order, linked to their pages.
std::string reports_section(const std::vector<SessionLink>& sessions) {
  if (sessions.empty()) return {};
  std::string html = "<h2>Session reports</h2>\n<table>\n<tr><th>trainee</th><th>sessions</th></tr>\n";
  for (std::size_t i = 0; i < sessions.size();) {
    const std::string& trainee = sessions[i].trainee;
    html += "<tr id=\"r-" + html_escape(trainee_file_stem(trainee)) + "\"><td>" + shown(trainee) +
            "</td><td class=\"links\">";
    for (; i < sessions.size() && sessions[i].trainee == trainee; ++i) {
      const auto& s = sessions[i];
      html += fmt::format("<a href=\"{}\" class=\"{}\">{} {}</a>", html_escape(s.href),
                          s.outcome == "passed" ? "ok" : "bad", shown(s.started_at), html_escape(s.outcome));
    }
    html += "</td></tr>\n";
  }
  return html + "</table>\n";
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
  for (const auto& s : skipped) {
    html += "<tr><td>" + shown(s.file, 2 * kShownChars) + "</td><td>" + shown(s.error, kShownErrorChars) +
            "</td></tr>\n";
  }
  return html + "</table>\n";
}

std::string page_head(const CohortPage& page) {
  std::size_t sessions = 0;
  for (const auto& t : page.trainees) sessions += t.attempts.size();
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<title>Palpa cohort report</title>\n<style>\n" + report_css() + kCohortCss +
                     "</style>\n</head>\n<body>\n";
  html += fmt::format("<h1>Cohort report</h1>\n<p class=\"meta\">Covers {}. {} sessions in the learning curves, {} trainee(s), "
                      "{} files skipped.</p>\n",
                      html_escape(page.selection.empty() ? std::string("every session given")
                                                         : printable(page.selection, 200)),
                      sessions, page.trainees.size(), page.skipped.size());
  for (const auto& note : page.notes) html += "<p class=\"note\">" + html_escape(note) + "</p>\n";
  return html;
}

}  // namespace

std::string relative_href(std::string_view folder, std::string_view stem, std::string_view extension) {
  std::string href(folder);
  href += '/';
  for (const char c : stem) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '_' || c == '-';
    if (keep) href += c;
    else href += fmt::format("%{:02X}", static_cast<unsigned char>(c));
  }
  href += extension;
  return href;
}

std::string cohort_html(const CohortPage& page, const CusumDesign& design, const ProficiencyRule& rule) {
  std::string html = page_head(page);
  html += "<h2>Trainees</h2>\n<table>\n<tr><th>trainee</th><th>sessions</th><th>passed</th><th>mean score</th>"
          "<th>last score</th><th>verdict</th><th>CUSUM</th></tr>\n";
  for (const auto& t : page.trainees) html += trainee_row(t, design);
  html += "</table>\n" + summaries_section(page) + case_curves_section(page.case_curves, design);
  html += method_text(design, rule);
  for (const auto& t : page.trainees) {
    html += "<h2 id=\"t-" + html_escape(t.file_stem) + "\">" + shown(t.trainee) + ": " +
            html_escape(t.proficiency.headline()) + "</h2>\n";
    html += png_img(t.png, "learning curve of " + printable(t.trainee, kShownChars)) + "\n";
    if (!page.sessions.empty()) html += "<p><a href=\"#r-" + html_escape(t.file_stem) + "\">Session reports</a></p>\n";
  }
  html += reports_section(page.sessions);
  html += skipped_section(page.skipped);
  html += "</body>\n</html>\n";
  return html;
}

std::string cohort_html(const std::vector<TraineeCurve>& trainees, const std::vector<SkippedFile>& skipped,
                        const std::string& selection, const CusumDesign& design, const ProficiencyRule& rule) {
  CohortPage page;
  page.trainees = trainees;
  page.skipped = skipped;
  page.selection = selection;
  return cohort_html(page, design, rule);
}

}  // namespace palpa::report
