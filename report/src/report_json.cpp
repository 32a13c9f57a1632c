#include "palpa/report/report_json.hpp"

namespace palpa::report {

nlohmann::json report_json(const SessionHeader& header, const score::Score& score) {
  nlohmann::json j = score::to_json(score, false);
  j["session"] = to_json(header);
  return j;
}

}  // namespace palpa::report
