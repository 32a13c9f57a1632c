#pragma once
// The learning-curve verdict: a proficiency rule of consecutive passes, as proficiency-based
// skills curricula do (Ritter & Scott 2007, Surgical Innovation 14:107-112: training goes on
// until the trainee performs at the expert-derived level on consecutive attempts).
//
// A trainee is proficient after an attempt when that attempt and the ones just before it
// passed, `consecutive` (3) in a row. A later failure ends it; three new passes in a row
// regain it. So the verdict always follows the latest attempts, whatever came before
// (six failures then three passes: proficient). The CUSUM chart (learning_curve.hpp) is
// kept beside it as supporting evidence about the failure rate.
#include <cstddef>
#include <string>
#include <vector>

namespace palpa::report {

struct ProficiencyRule {
  std::size_t consecutive = 3;  ///< passes in a row that make a trainee proficient
  std::size_t window = 5;       ///< "k of the last N passed" looks back this many attempts
};

struct Proficiency {
  std::vector<bool> proficient;      ///< after each attempt
  std::vector<std::string> verdict;  ///< words after each attempt
  /// The verdict after the last attempt, "no attempts" before the first.
  std::string headline() const;
  /// Proficient after the last attempt.
  bool now() const { return !proficient.empty() && proficient.back(); }
};

/// The verdict after each attempt in order (true: the attempt passed), in words:
///   "proficient since attempt 7"
///   "not yet: 2 of the last 5 passed" ("2 of 3 passed" while there are fewer than 5 attempts)
///   "proficient at attempts 4-9; failed attempt 10: not yet again (3 of the last 5 passed)"
Proficiency proficiency(const std::vector<bool>& passed, const ProficiencyRule& rule = {});

}  // namespace palpa::report
