#include <fmt/format.h>

#include "palpa/score/score.hpp"
#include "palpa/score/figures.hpp"

namespace palpa::score {
namespace {

using nlohmann::json;

json region_json(const Thresholds& t) {
  json out = json::array();
  for (const auto& p : t.exam_region) out.push_back({{"body", p.body}, {"u", {p.u0, p.u1}}, {"v", {p.v0, p.v1}}});
  return out;
}

}  // namespace

nlohmann::json to_json(const Score& s, bool with_maps) {
  json out = json::object();
  out["passed"] = s.passed;
  out["score"] = s.score;
  out["sensitivity"] = s.sensitivity;
  out["false_positives"] = s.false_positives;
  out["localization_error_mm"] = s.localization_error_mm;
  out["coverage"] = s.coverage;
  out["deep_coverage"] = s.deep_coverage;
  out["duration_s"] = s.duration_s;
  out["contact_time_s"] = s.contact_time_s;
  out["peak_force_n"] = s.peak_force_n;
  out["safe"] = s.safe;
  out["short_exam"] = s.short_exam;
  out["palpate_search_ratio"] = s.palpate_search_ratio;
  out["pressure"] = {{"light_s", s.pressure.light_s}, {"medium_s", s.pressure.medium_s}, {"deep_s", s.pressure.deep_s}};
  out["pattern"] = {{"kind", to_string(s.pattern.kind)},
                    {"path_length_m", s.pattern.path_length_m},
                    {"strip_fraction", s.pattern.strip_fraction},
                    {"strip_spacing_mm", s.pattern.strip_spacing_mm},
                    {"revisit_fraction", s.pattern.revisit_fraction},
                    {"efficiency", s.pattern.efficiency}};
  json gates = json::array();
  for (const auto& g : s.gates)
    gates.push_back({{"name", g.name}, {"passed", g.passed}, {"value", g.value}, {"threshold", g.threshold},
                     {"message", g.message}});
  out["gates"] = std::move(gates);
  json subscores = json::array();
  for (const auto& x : s.subscores) subscores.push_back({{"name", x.name}, {"value", x.value}, {"weight", x.weight}});
  out["subscores"] = std::move(subscores);
  json tumours = json::array();
  for (const auto& t : s.tumours) {
    json o = {{"body", t.body}, {"center", t.center}, {"radius", t.radius}, {"detectable", t.detectable},
              {"found", t.found}};
    o["mark"] = t.found ? json(t.mark) : json(nullptr);
    o["localization_error_mm"] = t.found ? json(t.localization_error_mm) : json(nullptr);
    tumours.push_back(std::move(o));
  }
  out["tumours"] = std::move(tumours);
  json marks = json::array();
  for (const auto& m : s.marks) {
    json o = {{"id", m.id}, {"t", m.t}, {"position", m.position}, {"duplicate", m.duplicate},
              {"false_positive", m.tumour < 0 && !m.duplicate}};
    o["tumour"] = m.tumour >= 0 ? json(m.tumour) : json(nullptr);
    o["nearest_mm"] = s.tumours.empty() ? json(nullptr) : json(m.nearest_mm);
    marks.push_back(std::move(o));
  }
  out["marks"] = std::move(marks);
  out["notes"] = s.notes;
  out["thresholds"] = to_json(s.thresholds);
  out["exam_region"] = region_json(s.thresholds);
  out["complete"] = s.complete;
  out["abandoned"] = s.abandoned;
  out["samples"] = s.samples;
  if (with_maps) {
    json maps = json::array();
    for (const auto& m : s.maps) {
      maps.push_back({{"body", m.body},
                      {"rows", m.rows},
                      {"cols", m.cols},
                      {"area", m.area},
                      {"center", m.center},
                      {"level", m.level},
                      {"dwell_s", m.dwell_s},
                      {"peak_force_n", m.peak_force_n}});
    }
    out["maps"] = std::move(maps);
  }
  return out;
}

std::string summary_text(const Score& s) {
  std::string out;
  out += s.abandoned ? "ABANDONED (not an exam)" : s.passed ? "PASSED" : "NOT PASSED";
  out += fmt::format("  score {:.1f} / 100\n", 100.0 * s.score);
  int found = 0;
  for (const auto& t : s.tumours) found += t.found ? 1 : 0;
  out += fmt::format("tumours found     {} of {}", found, s.tumours.size());
  out += " (sensitivity " + percent_text(s.sensitivity) + ")\n";
  out += fmt::format("false positives   {}\n", s.false_positives);
  if (!s.localization_error_mm.empty()) {
    out += "localization      ";
    for (std::size_t k = 0; k < s.localization_error_mm.size(); ++k)
      out += (k == 0 ? "" : ", ") + mm_text(s.localization_error_mm[k]);
    out += "\n";
  }
  out += "coverage          " + percent_text(s.coverage) + " (deep " + percent_text(s.deep_coverage) + ")\n";
  out += fmt::format("duration          {:.0f} s active, {:.0f} s in contact\n", s.duration_s, s.contact_time_s);
  const double contact = s.contact_time_s > 0 ? s.contact_time_s : 1.0;
  out += fmt::format("pressure          light {:.0f}%, medium {:.0f}%, ", 100.0 * s.pressure.light_s / contact,
                     100.0 * s.pressure.medium_s / contact);
  out += fmt::format("deep {:.0f}%\n", 100.0 * s.pressure.deep_s / contact);
  out += "peak force        " + force_text(s.peak_force_n) + "\n";
  out += fmt::format("palpate/search    {:.2f}\n", s.palpate_search_ratio);
  out += "search pattern    " + to_string(s.pattern.kind);
  out += fmt::format(" (strips {:.0f}%, spacing {:.0f} mm, ", 100.0 * s.pattern.strip_fraction,
                     s.pattern.strip_spacing_mm);
  out += fmt::format("revisits {:.0f}%)\n", 100.0 * s.pattern.revisit_fraction);
  for (const auto& g : s.gates) out += std::string(g.passed ? "PASS " : "FAIL ") + g.message + "\n";
  for (const auto& n : s.notes) out += "note: " + n + "\n";
  return out;
}

}  // namespace palpa::score
