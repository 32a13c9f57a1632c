#include "palpa/io/thresholds.hpp"

#include <cmath>
#include <set>

#include <fmt/format.h>

namespace palpa::io {
namespace {

using nlohmann::json;

// The allowed range of one "scoring" value (docs/scoring.md, "Case fields").
struct Range {
  double lo;
  double hi;
  bool lo_open;
  const char* unit;  // "" for fractions and ratios
};

constexpr Range kFraction{0.0, 1.0, false, ""};
constexpr Range kLength{0.0, 1.0, true, "m"};
constexpr Range kForce{0.0, 1000.0, true, "N"};
constexpr Range kRatio{0.0, 10.0, true, ""};
constexpr Range kWeight{0.0, 1000.0, false, ""};
// The coverage sub-score rises from 0 at coverage 0.5 to 1 at expert_coverage.
constexpr Range kExpert{0.5, 1.0, true, ""};
constexpr Range kSeconds{0.0, 86400.0, false, "s"};

struct Field {
  const char* name;
  double Thresholds::*member;
  Range range;
};

constexpr Field kFields[] = {
    {"hit_margin", &Thresholds::hit_margin, kLength},
    {"detectable_diameter", &Thresholds::detectable_diameter, kLength},
    {"pad_radius", &Thresholds::pad_radius, kLength},
    {"min_coverage", &Thresholds::min_coverage, kFraction},
    {"min_deep_coverage", &Thresholds::min_deep_coverage, kFraction},
    {"expert_coverage", &Thresholds::expert_coverage, kExpert},
    {"light_max", &Thresholds::light_max, kFraction},
    {"deep_min", &Thresholds::deep_min, kFraction},
    {"max_force", &Thresholds::max_force, kForce},
    {"palpate_radius", &Thresholds::palpate_radius, kLength},
    {"palpate_ratio_low", &Thresholds::palpate_ratio_low, kRatio},
    {"palpate_ratio_high", &Thresholds::palpate_ratio_high, kRatio},
    {"strip_spacing", &Thresholds::strip_spacing, kLength},
    {"min_duration", &Thresholds::min_duration, kSeconds},
    {"weight_sensitivity", &Thresholds::weight_sensitivity, kWeight},
    {"weight_false_positives", &Thresholds::weight_false_positives, kWeight},
    {"weight_localization", &Thresholds::weight_localization, kWeight},
    {"weight_coverage", &Thresholds::weight_coverage, kWeight},
    {"weight_deep_coverage", &Thresholds::weight_deep_coverage, kWeight},
    {"weight_pattern", &Thresholds::weight_pattern, kWeight},
    {"weight_pressure", &Thresholds::weight_pressure, kWeight},
};
constexpr const char* kMaxFalsePositives = "max_false_positives";
constexpr int kMaxFalsePositivesLimit = 1000;

std::string range_text(const Range& r) {
  return fmt::format("{}{:.6g}, {:.6g}]{}{}", r.lo_open ? "(" : "[", r.lo, r.hi, *r.unit != '\0' ? " " : "", r.unit);
}

bool read_number(const json& value, const std::string& where, const char* name, const Range& range,
                 std::vector<Problem>& problems, double& out) {
  if (!value.is_number()) {
    problems.push_back({where, std::string(name) + " must be a number, not " + value.type_name()});
    return false;
  }
  const double x = value.get<double>();
  if (!std::isfinite(x) || x < range.lo || (range.lo_open && x == range.lo) || x > range.hi) {
    problems.push_back({where, fmt::format("{} {:.6g} is outside {}", name, x, range_text(range))});
    return false;
  }
  out = x;
  return true;
}

std::string known_keys() {
  std::string s;
  for (const auto& f : kFields) {
    s += s.empty() ? "" : ", ";
    s += f.name;
  }
  s += ", ";
  s += kMaxFalsePositives;
  return s;
}

void read_scoring(const json& scoring, Thresholds& t, std::vector<Problem>& problems) {
  if (!scoring.is_object()) {
    problems.push_back({"/scoring", std::string("scoring must be an object, not ") + scoring.type_name()});
    return;
  }
  const Thresholds defaults;
  std::set<std::string> bad;  // keys whose value was rejected (their defaults stay)
  for (const auto& [key, value] : scoring.items()) {
    const std::string where = "/scoring/" + key;
    if (key == kMaxFalsePositives) {
      const bool integral = value.is_number_integer() ||
                            (value.is_number_float() && std::isfinite(value.get<double>()) &&
                             std::trunc(value.get<double>()) == value.get<double>());
      if (!integral) {
        problems.push_back({where, std::string(kMaxFalsePositives) + " must be an integer, not " +
                                       (value.is_number() ? std::string("a fraction") : std::string(value.type_name()))});
        bad.insert(key);
        continue;
      }
      const double n = value.get<double>();
      if (n < 0 || n > kMaxFalsePositivesLimit) {
        problems.push_back(
            {where, fmt::format("{} {:.6g} is outside [0, {}]", kMaxFalsePositives, n, kMaxFalsePositivesLimit)});
        bad.insert(key);
        continue;
      }
      t.max_false_positives = static_cast<int>(n);
      continue;
    }
    const Field* field = nullptr;
    for (const auto& f : kFields)
      if (key == f.name) field = &f;
    if (field == nullptr) {
      // A typo would silently leave a pass mark at its default: reject it.
      problems.push_back({where, "unknown scoring key \"" + key + "\" (known: " + known_keys() + ")"});
      continue;
    }
    if (!read_number(value, where, field->name, field->range, problems, t.*(field->member))) bad.insert(key);
  }

  // Relations between fields, checked only when both sides read cleanly.
  auto ok = [&](const char* key) { return !bad.contains(key); };
  if (ok("light_max") && ok("deep_min") && !(t.light_max < t.deep_min)) {
    problems.push_back({scoring.contains("deep_min") ? "/scoring/deep_min" : "/scoring/light_max",
                        fmt::format("light_max {:.6g} must be below deep_min {:.6g} (light < medium < deep pressure)",
                                    t.light_max, t.deep_min)});
    t.light_max = defaults.light_max;
    t.deep_min = defaults.deep_min;
  }
  if (ok("palpate_ratio_low") && ok("palpate_ratio_high") && t.palpate_ratio_low > t.palpate_ratio_high) {
    problems.push_back({scoring.contains("palpate_ratio_high") ? "/scoring/palpate_ratio_high"
                                                               : "/scoring/palpate_ratio_low",
                        fmt::format("palpate_ratio_low {:.6g} is above palpate_ratio_high {:.6g}",
                                    t.palpate_ratio_low, t.palpate_ratio_high)});
    t.palpate_ratio_low = defaults.palpate_ratio_low;
    t.palpate_ratio_high = defaults.palpate_ratio_high;
  }
  const double sum = t.weight_sensitivity + t.weight_false_positives + t.weight_localization + t.weight_coverage +
                     t.weight_deep_coverage + t.weight_pattern + t.weight_pressure;
  if (!(sum > 0.0)) {
    problems.push_back({"/scoring", "the weights sum to 0: at least one weight_* must be positive"});
    for (const auto& f : kFields)
      if (std::string_view(f.name).starts_with("weight_")) t.*(f.member) = defaults.*(f.member);
  }
}

// [a, b] with 0 <= a < b <= 1, or absent (the whole parameter range).
void read_interval(const json& part, const std::string& base, const char* key, double& lo, double& hi,
                   std::vector<Problem>& problems) {
  if (!part.contains(key)) return;
  const std::string where = base + "/" + key;
  const json& value = part[key];
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
    problems.push_back({where, std::string(key) + " must be an array of two numbers [" + key + "0, " + key + "1]"});
    return;
  }
  const double a = value[0].get<double>();
  const double b = value[1].get<double>();
  if (!(std::isfinite(a) && std::isfinite(b) && 0.0 <= a && a < b && b <= 1.0)) {
    problems.push_back({where, fmt::format("{0} [{1:.6g}, {2:.6g}] must satisfy 0 <= {0}0 < {0}1 <= 1", key, a, b)});
    return;
  }
  lo = a;
  hi = b;
}

void read_region(const json& doc, const json& region, Thresholds& t, std::vector<Problem>& problems) {
  if (!region.is_array() || region.empty()) {
    problems.push_back({"/exam_region", "exam_region must be a non-empty array of {\"body\", \"u\", \"v\"} "
                                        "(leave it out to examine every body's whole top contour)"});
    return;
  }
  // Body ids as the document names them; unknown-body checks only make sense when they read.
  std::set<std::string> ids;
  bool ids_known = doc.contains("bodies") && doc["bodies"].is_array();
  if (ids_known) {
    for (const auto& b : doc["bodies"]) {
      if (b.is_object() && b.contains("id") && b["id"].is_string()) ids.insert(b["id"].get<std::string>());
    }
  }
  std::vector<RegionPart> parts;
  for (std::size_t k = 0; k < region.size(); ++k) {
    const std::string base = fmt::format("/exam_region/{}", k);
    const json& p = region[k];
    if (!p.is_object()) {
      problems.push_back({base, "an exam region part must be an object {\"body\", \"u\", \"v\"}"});
      continue;
    }
    const std::size_t before = problems.size();
    RegionPart part;
    for (const auto& [key, value] : p.items()) {
      (void)value;
      if (key != "body" && key != "u" && key != "v")
        problems.push_back({base + "/" + key, "unknown exam region key \"" + key + "\" (known: body, u, v)"});
    }
    if (!p.contains("body")) {
      problems.push_back({base, "missing \"body\""});
    } else if (!p["body"].is_string()) {
      problems.push_back({base + "/body", "body must be a body id (a string)"});
    } else {
      part.body = p["body"].get<std::string>();
      if (ids_known && !ids.contains(part.body)) {
        std::string known;
        for (const auto& id : ids) known += (known.empty() ? "" : ", ") + id;
        problems.push_back({base + "/body", "unknown body \"" + part.body + "\" (bodies: " + known + ")"});
      }
    }
    read_interval(p, base, "u", part.u0, part.u1, problems);
    read_interval(p, base, "v", part.v0, part.v1, problems);
    if (problems.size() == before) parts.push_back(std::move(part));
  }
  if (parts.size() == region.size()) t.exam_region = std::move(parts);
}

}  // namespace

Thresholds thresholds_from_case(const nlohmann::json& case_document, std::vector<Problem>& problems) {
  Thresholds t;
  if (!case_document.is_object()) return t;
  if (case_document.contains("scoring")) read_scoring(case_document["scoring"], t, problems);
  if (case_document.contains("exam_region")) read_region(case_document, case_document["exam_region"], t, problems);
  return t;
}

nlohmann::json to_json(const Thresholds& t) {
  json out = json::object();
  for (const auto& f : kFields) out[f.name] = t.*(f.member);
  out[kMaxFalsePositives] = t.max_false_positives;
  return out;
}

}  // namespace palpa::io
