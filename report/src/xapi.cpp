#include "palpa/report/xapi.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "palpa/report/encoding.hpp"
#include "palpa/report/summary_csv.hpp"
#include "palpa/version.hpp"

namespace palpa::report {

std::string iso8601_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0) return "PT0S";
  const auto centis = static_cast<long long>(std::llround(seconds * 100.0));
  std::string text = fmt::format("PT{}", centis / 100);
  const long long frac = centis % 100;
  if (frac != 0) {
    text += '.';
    text += static_cast<char>('0' + frac / 10);
    if (frac % 10 != 0) text += static_cast<char>('0' + frac % 10);
  }
  text += 'S';
  return text;
}

nlohmann::json xapi_statement(const SessionHeader& h, const score::Score& s, const std::string& home_page) {
  using nlohmann::json;
  const double scaled = std::clamp(std::isfinite(s.score) ? s.score : 0.0, 0.0, 1.0);
  const std::string verb = s.passed ? "passed" : "failed";
  const double loc = mean_localization_error_mm(s);
  const std::string x = "urn:palpa:xapi:";
  json extensions = {{x + "sensitivity", s.sensitivity},
                     {x + "false_positives", s.false_positives},
                     {x + "localization_error_mm", std::isfinite(loc) ? json(loc) : json(nullptr)},
                     {x + "coverage", s.coverage},
                     {x + "deep_coverage", s.deep_coverage},
                     {x + "contact_time_s", s.contact_time_s},
                     {x + "peak_force_n", s.peak_force_n},
                     {x + "safe", s.safe},
                     {x + "palpate_search_ratio", s.palpate_search_ratio},
                     {x + "pattern", score::to_string(s.pattern.kind)},
                     {x + "light_s", s.pressure.light_s},
                     {x + "medium_s", s.pressure.medium_s},
                     {x + "deep_s", s.pressure.deep_s},
                     {x + "tumours", s.tumours.size()},
                     {x + "tumours_found",
                      std::count_if(s.tumours.begin(), s.tumours.end(), [](const auto& t) { return t.found; })}};
  std::string description = "Palpation exercise: find and mark the hidden tumours of the case";
  if (!h.case_source.empty()) description += " (" + h.case_source + ")";
  description += '.';
  const std::string version = h.software_version.empty() ? std::string(palpa::kVersion) : h.software_version;
  json statement = {
      {"id", uuid_v5(kPalpaNamespace, h.id)},
      {"version", "1.0.3"},
      {"actor", {{"objectType", "Agent"}, {"account", {{"homePage", home_page}, {"name", h.trainee}}}}},
      {"verb", {{"id", "http://adlnet.gov/expapi/verbs/" + verb}, {"display", {{"en-US", verb}}}}},
      {"object",
       {{"objectType", "Activity"},
        {"id", case_activity_id(h)},
        {"definition",
         {{"name", {{"en-US", case_name(h)}}},
          {"description", {{"en-US", description}}},
          {"type", "http://adlnet.gov/expapi/activities/simulation"}}}}},
      {"result",
       {{"score", {{"scaled", scaled}, {"raw", std::round(scaled * 10000.0) / 100.0}, {"min", 0}, {"max", 100}}},
        {"success", s.passed},
        {"completion", s.complete},
        {"duration", iso8601_duration(s.duration_s)},
        {"extensions", extensions}}},
      {"context",
       {{"platform", "Palpa " + version},
        {"extensions", {{x + "session_id", h.id}, {x + "device", h.device}}}}}};
  if (!h.started_at.empty()) statement["timestamp"] = h.started_at;
  return statement;
}

}  // namespace palpa::report
