#pragma once
// What a case sets for the trainee window while she works (docs/case-format.md,
// "training"): an optional object of the case, e.g. {"training": {"coverage_overlay": false}}
// for an exam. Its keys are Palpa's own, so unknown ones are errors (typos), as in "scoring".
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/io/case_file.hpp"

namespace palpa::io {

struct TrainingOptions {
  /// The live coverage overlay on the body and the live coverage figure (true: on by
  /// default, the trainee may turn it off; false: never shown, an exam).
  bool coverage_overlay = true;
};

/// The case's "training" object read and checked; each problem (JSON pointer, reason) is
/// appended to `problems` and the default kept.
TrainingOptions training_from_case(const nlohmann::json& case_document, std::vector<Problem>& problems);

/// Same, for a case that was validated already (load_case): problems are ignored.
TrainingOptions training_from_case(const nlohmann::json& case_document);

}  // namespace palpa::io
