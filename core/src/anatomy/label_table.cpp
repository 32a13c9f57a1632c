// Label tables (docs/anatomy-import.md, "Label tables"): parsed strictly, since a misspelt
// class would silently turn tissue into air.
#include "palpa/anatomy/label_table.hpp"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/io/json_text.hpp"

namespace palpa::anatomy {

namespace {

using nlohmann::json;

constexpr double kMaxModulus = 1e9;  // Pa, as in case files

[[noreturn]] void fail(const std::string& source, const std::string& where, const std::string& why) {
  throw ImportError(fmt::format("{}: {}: {}", source, where, why));
}

LabelClass parse_class(const json& value, const std::string& source, const std::string& where) {
  static const std::pair<const char*, LabelClass> kClasses[] = {{"outside", LabelClass::Outside},
                                                                 {"tissue", LabelClass::Tissue},
                                                                 {"skin", LabelClass::Skin},
                                                                 {"support", LabelClass::Support},
                                                                 {"lesion", LabelClass::Lesion}};
  if (value.is_string()) {
    for (const auto& [name, kind] : kClasses) {
      if (value.get<std::string>() == name) return kind;
    }
  }
  fail(source, where, "class must be one of \"tissue\", \"skin\", \"support\", \"lesion\", \"outside\"");
}

// Any integer as segmentation tools write it: "-4", "0", "12"; no "+", "-0" or leading 0.
Label parse_label_key(const std::string& key, const std::string& source) {
  Label label = 0;
  const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), label);
  const std::string_view digits = key.starts_with('-') ? std::string_view(key).substr(1) : std::string_view(key);
  if (error != std::errc{} || end != key.data() + key.size() || digits.empty() ||
      (digits.size() > 1 && digits[0] == '0') || key == "-0") {
    fail(source, "/labels", fmt::format("label \"{}\" is not an integer (such as -4, 0 or 12)", key.substr(0, 32)));
  }
  return label;
}

double parse_number(const json& entry, const char* field, const std::string& source, const std::string& where,
                    double hi) {
  const json& v = entry.at(field);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0 || v.get<double>() > hi) {
    fail(source, where + "/" + field, fmt::format("{} must be a number in [0, {:g}]", field, hi));
  }
  return v.get<double>();
}

LabelEntry parse_entry(const json& entry, const std::string& source, const std::string& where) {
  if (!entry.is_object()) fail(source, where, "must be an object with class, name and modulus");
  for (const auto& [key, value] : entry.items()) {
    if (key != "class" && key != "name" && key != "modulus" && key != "stiffening") {
      fail(source, where + "/" + key.substr(0, 32), "unknown field (known: class, name, modulus, stiffening)");
    }
  }
  if (!entry.contains("class")) fail(source, where + "/class", "missing");
  LabelEntry out;
  out.kind = parse_class(entry.at("class"), source, where + "/class");
  if (entry.contains("name")) {
    if (!entry.at("name").is_string() || entry.at("name").get<std::string>().size() > kMaxLabelNameLength) {
      fail(source, where + "/name", fmt::format("name must be a string of at most {} bytes", kMaxLabelNameLength));
    }
    out.name = entry.at("name").get<std::string>();
  }
  const bool needs_modulus = LabelTable::soft(out.kind);
  if (needs_modulus && !entry.contains("modulus")) fail(source, where + "/modulus", "missing (Pa; required for tissue, skin and lesion)");
  if (entry.contains("modulus")) out.modulus = parse_number(entry, "modulus", source, where, kMaxModulus);
  if (needs_modulus && out.modulus <= 0.0) fail(source, where + "/modulus", "must be above 0 Pa");
  if (entry.contains("stiffening")) out.stiffening = parse_number(entry, "stiffening", source, where, 20.0);
  return out;
}

}  // namespace

const char* to_string(LabelClass kind) {
  switch (kind) {
    case LabelClass::Tissue: return "tissue";
    case LabelClass::Skin: return "skin";
    case LabelClass::Support: return "support";
    case LabelClass::Lesion: return "lesion";
    case LabelClass::Outside: break;
  }
  return "outside";
}

const LabelEntry* LabelTable::find(Label label) const {
  const auto it = labels.find(label);
  return it == labels.end() ? nullptr : &it->second;
}

LabelTable parse_label_table(std::string_view text, const std::string& source) {
  if (text.size() > kMaxLabelTableBytes) fail(source, "/", fmt::format("larger than {} bytes", kMaxLabelTableBytes));
  json doc;
  if (const auto problem = io::parse_json_text(text, 8, 4 * kMaxLabels * 4, doc)) fail(source, problem->where, problem->reason);
  if (!doc.is_object() || !doc.contains("labels") || !doc.at("labels").is_object()) {
    fail(source, "/labels", "missing: a table is {\"labels\": {\"<label>\": {\"class\": ..., \"modulus\": ...}}}");
  }
  for (const auto& [key, value] : doc.items()) {
    if (key != "labels" && key != "name" && key != "source") fail(source, "/" + key.substr(0, 32), "unknown field (known: labels, name, source)");
  }
  const json& labels = doc.at("labels");
  if (labels.empty()) fail(source, "/labels", "is empty");
  if (labels.size() > kMaxLabels) fail(source, "/labels", fmt::format("more than {} labels", kMaxLabels));
  LabelTable table;
  table.name = source;
  for (const auto& [key, value] : labels.items()) {
    const Label label = parse_label_key(key, source);
    table.labels[label] = parse_entry(value, source, "/labels/" + key);
  }
  const auto span = static_cast<std::int64_t>(table.labels.rbegin()->first) - table.labels.begin()->first;
  if (span >= static_cast<std::int64_t>(kMaxLabelSpan)) {
    fail(source, "/labels", fmt::format("labels from {} to {}: they may span at most {} values",
                                        table.labels.begin()->first, table.labels.rbegin()->first, kMaxLabelSpan));
  }
  return table;
}

}  // namespace palpa::anatomy
