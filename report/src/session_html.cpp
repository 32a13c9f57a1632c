#include "palpa/report/session_html.hpp"

#include <cmath>

#include <fmt/format.h>

#include "palpa/report/encoding.hpp"
#include "palpa/report/images.hpp"
#include "palpa/report/summary_csv.hpp"
#include "palpa/report/printable.hpp"
#include "palpa/score/figures.hpp"

namespace palpa::report {
namespace {

// Every field of a session file is the station's text: control and bidirectional
// characters are shown as escapes (printable.hpp), then the markup is escaped.
std::string esc(std::string_view s) { return html_escape(printable(s, 400)); }

/// Fixed decimals for people; "-" when not finite.
std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  return fmt::format("{:.{}f}", v, decimals);
}
std::string percent(double fraction) { return std::isfinite(fraction) ? fixed(100.0 * fraction, 1) + " %" : "-"; }
std::string mm(double metres) { return fixed(metres * 1e3, 1) + " mm"; }

void row(std::string& html, std::string_view name, std::string_view value) {
  html += "<tr><th>";
  html += esc(name);
  html += "</th><td>";
  html += esc(value);
  html += "</td></tr>\n";
}

std::string position_mm(const std::array<double, 3>& p) {
  std::string text = "(";
  text += fixed(p[0] * 1e3, 1);
  text += ", ";
  text += fixed(p[1] * 1e3, 1);
  text += ", ";
  text += fixed(p[2] * 1e3, 1);
  text += ")";
  return text;
}

}  // namespace

const std::string& report_css() {
  static const std::string kCss = R"(body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;color:#222;line-height:1.4}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.15em;margin-top:1.6em;border-bottom:1px solid #ddd;padding-bottom:.2em}
.meta{color:#555;margin-top:0}.banner{padding:.8em 1em;border-radius:6px;margin:1em 0}
.pass{background:#e6f4ea;border:1px solid #6bb37e}.fail{background:#fdecea;border:1px solid #d9534f}
.banner strong{font-size:1.2em}.banner ul{margin:.4em 0 0 1.2em;padding:0}
table{border-collapse:collapse;margin:.5em 0}th,td{padding:.25em .8em;border-bottom:1px solid #eee;text-align:left;vertical-align:top}
td.num{text-align:right;font-variant-numeric:tabular-nums}.ok{color:#1e7b34}.bad{color:#b52a25}
img{max-width:100%;height:auto;border:1px solid #ddd;margin:.5em 0}
)";
  return kCss;
}

std::string png_img(const std::vector<std::uint8_t>& png, const std::string& alt) {
  return "<img alt=\"" + esc(alt) + "\" src=\"data:image/png;base64," + base64(png) + "\">";
}

SessionImages render_images(const session::Session& session, const score::Score& score) {
  return {png_bytes(coverage_heatmap(score)), png_bytes(pressure_map(score)), png_bytes(force_plot(session, score))};
}

SessionImages render_images(const ForceTrace& trace, const score::Score& score) {
  return {png_bytes(coverage_heatmap(score)), png_bytes(pressure_map(score)), png_bytes(force_plot(trace, score))};
}

namespace {

// The page head, what was palpated, and the verdict with its gates.
void add_head_and_verdict(std::string& html, const SessionHeader& h, const score::Score& s) {
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Palpa session ";
  html += esc(h.trainee) + " - " + esc(case_name(h)) + "</title>\n<style>\n" + report_css() + "</style>\n</head>\n<body>\n";
  html += "<h1>Palpation session: " + esc(h.trainee) + "</h1>\n";
  html += "<p class=\"meta\">Case <b>" + esc(case_name(h)) + "</b>";
  if (!h.case_source.empty()) html += " (" + esc(h.case_source) + ")";
  html += " &middot; started " + esc(h.started_at) + " &middot; device " + esc(h.device) + " &middot; Palpa " +
          esc(h.software_version) + "<br>Session " + esc(h.id) + " &middot; file " + esc(h.file) + "</p>\n";

  html += std::string("<div class=\"banner ") + (s.passed ? "pass" : "fail") + "\"><strong>" +
          (s.passed ? "PASSED" : "FAILED") + "</strong> &middot; score " + fixed(100.0 * s.score, 1) + " / 100\n<ul>\n";
  for (const auto& g : s.gates) {
    html += std::string("<li class=\"") + (g.passed ? "ok" : "bad") + "\">" + (g.passed ? "&#10003; " : "&#10007; ") +
            esc(g.message.empty() ? g.name : g.message) + "</li>\n";
  }
  html += "</ul></div>\n";

}

void add_metrics(std::string& html, const score::Score& s) {
  html += "<h2>Metrics</h2>\n<table>\n";
  std::size_t found = 0;
  for (const auto& t : s.tumours) found += t.found ? 1 : 0;
  row(html, "Sensitivity",
      fmt::format("{} ({} of {} tumours found)", score::percent_text(s.sensitivity), found, s.tumours.size()));
  row(html, "False positives", fmt::format("{}", s.false_positives));
  const double loc = mean_localization_error_mm(s);
  row(html, "Localization error (mean)", score::mm_text(loc));
  row(html, "Coverage", score::percent_text(s.coverage));
  row(html, "Deep coverage", score::percent_text(s.deep_coverage));
  row(html, "Duration", fixed(s.duration_s, 1) + " s" + (s.short_exam ? " (short exam)" : ""));
  row(html, "Contact time", fixed(s.contact_time_s, 1) + " s");
  row(html, "Time at light / medium / deep pressure", fixed(s.pressure.light_s, 1) + " / " +
                                                          fixed(s.pressure.medium_s, 1) + " / " +
                                                          fixed(s.pressure.deep_s, 1) + " s");
  row(html, "Peak force", score::force_text(s.peak_force_n) + (s.safe ? "" : " (over the safety limit)"));
  row(html, "Palpate / search force ratio", s.palpate_search_ratio > 0.0 ? fixed(s.palpate_search_ratio, 2) : "-");
  row(html, "Search pattern", score::to_string(s.pattern.kind) + " (strips " + percent(s.pattern.strip_fraction) + ", spacing " +
                                  fixed(s.pattern.strip_spacing_mm, 1) + " mm, revisits " +
                                  percent(s.pattern.revisit_fraction) + ", efficiency " +
                                  percent(s.pattern.efficiency) + ")");
  row(html, "Samples", fmt::format("{}{}", s.samples, s.complete ? "" : " (session incomplete)"));
  html += "</table>\n";
  if (!s.subscores.empty()) {
    // Points out of 100 add up to the score, so the page has one score scale (0-100).
    html += "<h2>Sub-scores</h2>\n<table>\n<tr><th>part</th><th>achieved</th><th>weight</th><th>points (of 100)</th>"
            "</tr>\n";
    for (const auto& sub : s.subscores)
      html += "<tr><td>" + esc(sub.name) + "</td><td class=\"num\">" + percent(sub.value) + "</td><td class=\"num\">" +
              percent(sub.weight) + "</td><td class=\"num\">" + fixed(100.0 * sub.weight * sub.value, 1) +
              "</td></tr>\n";
    html += "</table>\n";
  }

}

void add_tumours(std::string& html, const score::Score& s) {
  html += "<h2>Tumours</h2>\n<table>\n<tr><th>#</th><th>body</th><th>centre (mm)</th><th>diameter</th>"
          "<th>found</th><th>by mark</th><th>error</th></tr>\n";
  for (std::size_t i = 0; i < s.tumours.size(); ++i) {
    const auto& t = s.tumours[i];
    html += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}{}</td><td class=\"{}</td><td>{}</td>"
        "<td class=\"num\">{}</td></tr>\n",
        i + 1, esc(t.body), position_mm(t.center), mm(2.0 * t.radius), t.detectable ? "" : " (below detectable size)",
        t.found ? "ok\">yes" : "bad\">no", t.mark >= 0 ? fmt::format("{}", t.mark) : "-",
        t.found ? score::mm_text(t.localization_error_mm) : "-");
  }
  html += "</table>\n";

}

// The marks, then the notes.
void add_marks_and_notes(std::string& html, const score::Score& s) {
  html += "<h2>Marks</h2>\n";
  if (s.marks.empty()) {
    html += "<p>No marks.</p>\n";
  } else {
    html += "<table>\n<tr><th>mark</th><th>time</th><th>position (mm)</th><th>result</th>"
            "<th>nearest tumour</th></tr>\n";
    for (const auto& m : s.marks) {
      std::string result = m.tumour >= 0 ? fmt::format("hit tumour {}", m.tumour + 1) : "false positive";
      if (m.duplicate) result += " (duplicate)";
      html += fmt::format(
          "<tr><td>{}</td><td class=\"num\">{} s</td><td>{}</td><td>{}</td><td class=\"num\">{} mm</td></tr>\n", m.id,
          fixed(m.t, 2), position_mm(m.position), esc(result), fixed(m.nearest_mm, 1));
    }
    html += "</table>\n";
  }
  if (!s.notes.empty()) {
    html += "<h2>Notes</h2>\n<ul>\n";
    for (const auto& n : s.notes) html += "<li>" + esc(n) + "</li>\n";
    html += "</ul>\n";
  }

}

void add_thresholds(std::string& html, const score::Score& s) {
  const auto& th = s.thresholds;
  html += "<h2>Thresholds used</h2>\n<table>\n";
  row(html, "A mark hits a tumour within", "its radius + " + mm(th.hit_margin));
  row(html, "Smallest tumour counted for sensitivity", mm(th.detectable_diameter) + " diameter");
  row(html, "False positives allowed", fmt::format("{}", th.max_false_positives));
  row(html, "Coverage needed (expert)", score::percent_text(th.min_coverage) + " (" + score::percent_text(th.expert_coverage) + ")");
  row(html, "Deep coverage needed", score::percent_text(th.min_deep_coverage));
  row(html, "Finger pad radius", mm(th.pad_radius));
  row(html, "Pressure levels (depth / thickness)",
      "light below " + fixed(th.light_max, 2) + ", deep from " + fixed(th.deep_min, 2));
  row(html, "Safety limit on force", fixed(th.max_force, 1) + " N");
  row(html, "Palpate / search ratio target", fixed(th.palpate_ratio_low, 2) + " to " + fixed(th.palpate_ratio_high, 2));
  row(html, "Strip spacing", mm(th.strip_spacing));
  row(html, "Shortest exam not flagged", fixed(th.min_duration, 0) + " s");
  std::string region;
  for (const auto& part : th.exam_region) {
    if (!region.empty()) region += "; ";
    region += part.body + " u " + fixed(part.u0, 2) + "-" + fixed(part.u1, 2) + ", v " + fixed(part.v0, 2) + "-" +
              fixed(part.v1, 2);
  }
  row(html, "Exam region", region.empty() ? "the whole top of every body" : region);
  html += "</table>\n";
}

}  // namespace

std::string session_html(const SessionHeader& h, const score::Score& s, const SessionImages& images) {
  std::string html;
  add_head_and_verdict(html, h, s);
  add_metrics(html, s);
  html += "<h2>Coverage</h2>\n" + png_img(images.coverage, "coverage heatmap") + "\n";
  html += "<h2>Pressure</h2>\n" + png_img(images.pressure, "pressure map") + "\n";
  html += "<h2>Force over time</h2>\n" + png_img(images.force, "force and indentation level over time") + "\n";

  add_tumours(html, s);
  add_marks_and_notes(html, s);
  add_thresholds(html, s);
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace palpa::report
