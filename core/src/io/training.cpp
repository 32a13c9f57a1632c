#include "palpa/io/training.hpp"

#include <string>

namespace palpa::io {

TrainingOptions training_from_case(const nlohmann::json& doc, std::vector<Problem>& problems) {
  TrainingOptions out;
  if (!doc.is_object() || !doc.contains("training")) return out;
  const nlohmann::json& t = doc["training"];
  if (!t.is_object()) {
    problems.push_back({"/training", std::string("training must be an object, not ") + t.type_name()});
    return out;
  }
  for (const auto& [key, value] : t.items()) {
    if (key == "coverage_overlay") {
      if (value.is_boolean()) {
        out.coverage_overlay = value.get<bool>();
      } else {
        problems.push_back({"/training/coverage_overlay",
                            std::string("coverage_overlay must be true or false, not ") + value.type_name()});
      }
    } else {
      const std::string shown = key.size() > 40 ? key.substr(0, 40) + "..." : key;
      problems.push_back({"/training/" + key, "unknown training field \"" + shown + "\" (expected coverage_overlay)"});
    }
  }
  return out;
}

TrainingOptions training_from_case(const nlohmann::json& doc) {
  std::vector<Problem> ignored;
  return training_from_case(doc, ignored);
}

}  // namespace palpa::io
