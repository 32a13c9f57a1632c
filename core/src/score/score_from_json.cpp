// A score read back from its JSON (to_json): how a report takes a scoring worker's stored
// result instead of scoring the session again (docs/centre.md, "Reports from the store").
#include <stdexcept>

#include "palpa/score/score.hpp"

namespace palpa::score {
namespace {

using nlohmann::json;

PatternKind pattern_kind(const std::string& name) {
  for (const auto kind :
       {PatternKind::None, PatternKind::Sporadic, PatternKind::Localized, PatternKind::Thorough, PatternKind::Efficient}) {
    if (to_string(kind) == name) return kind;
  }
  throw std::invalid_argument("pattern.kind: not a search-pattern class");
}

void read_pattern(const json& j, SearchPattern& p) {
  p.kind = pattern_kind(j.at("kind").get<std::string>());
  p.path_length_m = j.at("path_length_m").get<double>();
  p.strip_fraction = j.at("strip_fraction").get<double>();
  p.strip_spacing_mm = j.at("strip_spacing_mm").get<double>();
  p.revisit_fraction = j.at("revisit_fraction").get<double>();
  p.efficiency = j.at("efficiency").get<double>();
}

void read_lists(const json& j, Score& s) {
  for (const auto& g : j.at("gates")) {
    s.gates.push_back({g.at("name").get<std::string>(), g.at("passed").get<bool>(), g.at("value").get<double>(),
                       g.at("threshold").get<double>(), g.at("message").get<std::string>()});
  }
  for (const auto& x : j.at("subscores")) {
    s.subscores.push_back({x.at("name").get<std::string>(), x.at("value").get<double>(), x.at("weight").get<double>()});
  }
  for (const auto& t : j.at("tumours")) {
    TumourResult r;
    r.body = t.at("body").get<std::string>();
    r.center = t.at("center").get<std::array<double, 3>>();
    r.radius = t.at("radius").get<double>();
    r.detectable = t.at("detectable").get<bool>();
    r.found = t.at("found").get<bool>();
    if (r.found) {
      r.mark = t.at("mark").get<std::int64_t>();
      r.localization_error_mm = t.at("localization_error_mm").get<double>();
    }
    s.tumours.push_back(std::move(r));
  }
  for (const auto& m : j.at("marks")) {
    MarkResult r;
    r.id = m.at("id").get<std::int64_t>();
    r.t = m.at("t").get<double>();
    r.position = m.at("position").get<std::array<double, 3>>();
    r.duplicate = m.at("duplicate").get<bool>();
    r.tumour = m.at("tumour").is_null() ? -1 : m.at("tumour").get<int>();
    if (r.tumour >= static_cast<int>(s.tumours.size())) throw std::invalid_argument("marks: tumour out of range");
    r.nearest_mm = m.at("nearest_mm").is_null() ? 0.0 : m.at("nearest_mm").get<double>();
    s.marks.push_back(r);
  }
}

void read_maps(const json& j, Score& s) {
  for (const auto& m : j) {
    BodyMap map;
    map.body = m.at("body").get<std::string>();
    map.rows = m.at("rows").get<int>();
    map.cols = m.at("cols").get<int>();
    map.area = m.at("area").get<std::vector<double>>();
    map.center = m.at("center").get<std::vector<std::array<float, 3>>>();
    map.level = m.at("level").get<std::vector<std::uint8_t>>();
    map.dwell_s = m.at("dwell_s").get<std::vector<float>>();
    map.peak_force_n = m.at("peak_force_n").get<std::vector<float>>();
    const auto cells = static_cast<std::size_t>(map.rows) * static_cast<std::size_t>(map.cols);
    if (map.rows < 0 || map.cols < 0 || map.area.size() != cells || map.center.size() != cells ||
        map.level.size() != cells || map.dwell_s.size() != cells || map.peak_force_n.size() != cells) {
      throw std::invalid_argument("maps: cell arrays do not match rows x cols");
    }
    s.maps.push_back(std::move(map));
  }
}

}  // namespace

Score score_from_json(const nlohmann::json& j, const Thresholds& thresholds) {
  Score s;
  try {
    s.passed = j.at("passed").get<bool>();
    s.score = j.at("score").get<double>();
    s.sensitivity = j.at("sensitivity").get<double>();
    s.false_positives = j.at("false_positives").get<int>();
    s.localization_error_mm = j.at("localization_error_mm").get<std::vector<double>>();
    s.coverage = j.at("coverage").get<double>();
    s.deep_coverage = j.at("deep_coverage").get<double>();
    s.duration_s = j.at("duration_s").get<double>();
    s.contact_time_s = j.at("contact_time_s").get<double>();
    s.peak_force_n = j.at("peak_force_n").get<double>();
    s.safe = j.at("safe").get<bool>();
    s.short_exam = j.at("short_exam").get<bool>();
    s.palpate_search_ratio = j.at("palpate_search_ratio").get<double>();
    const auto& p = j.at("pressure");
    s.pressure = {p.at("light_s").get<double>(), p.at("medium_s").get<double>(), p.at("deep_s").get<double>()};
    read_pattern(j.at("pattern"), s.pattern);
    read_lists(j, s);
    s.notes = j.at("notes").get<std::vector<std::string>>();
    s.complete = j.at("complete").get<bool>();
    s.abandoned = j.at("abandoned").get<bool>();
    s.samples = j.at("samples").get<std::uint64_t>();
    if (j.contains("maps")) read_maps(j.at("maps"), s);
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("stored score: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("stored score: ") + e.what());
  }
  s.thresholds = thresholds;
  return s;
}

}  // namespace palpa::score
