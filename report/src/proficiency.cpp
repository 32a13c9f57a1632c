#include "palpa/report/proficiency.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace palpa::report {
namespace {

/// The last proficient stretch: attempts `from`..`to` (from 1); 0 when there was none.
struct Stretch {
  std::size_t from = 0, to = 0;
};

std::string passes_in_window(const std::vector<bool>& passed, std::size_t n, std::size_t window) {
  const std::size_t w = std::min(std::max<std::size_t>(window, 1), n);
  const auto k = std::count(passed.begin() + static_cast<std::ptrdiff_t>(n - w),
                            passed.begin() + static_cast<std::ptrdiff_t>(n), true);
  // "of the last 5" once there are that many attempts; "2 of 3" (every attempt) before.
  return w < window ? fmt::format("{} of {} passed", k, w) : fmt::format("{} of the last {} passed", k, w);
}

std::string attempts_text(const Stretch& s) {
  return s.from == s.to ? fmt::format("attempt {}", s.from) : fmt::format("attempts {}-{}", s.from, s.to);
}

}  // namespace

std::string Proficiency::headline() const { return verdict.empty() ? std::string("no attempts") : verdict.back(); }

Proficiency proficiency(const std::vector<bool>& passed, const ProficiencyRule& rule) {
  const std::size_t needed = std::max<std::size_t>(rule.consecutive, 1);
  Proficiency p;
  std::size_t run = 0;  // passes in a row up to this attempt
  Stretch current, last;
  for (std::size_t i = 0; i < passed.size(); ++i) {
    const std::size_t attempt = i + 1;
    run = passed[i] ? run + 1 : 0;
    const bool now = run >= needed;
    if (now) {
      if (current.from == 0) current.from = attempt;
      current.to = attempt;
      last = current;
    } else {
      current = {};
    }
    p.proficient.push_back(now);
    if (now) {
      p.verdict.push_back(fmt::format("proficient since attempt {}", current.from));
    } else if (last.from == 0) {
      p.verdict.push_back("not yet: " + passes_in_window(passed, attempt, rule.window));
    } else {
      p.verdict.push_back(fmt::format("proficient at {}; failed attempt {}: not yet again ({})", attempts_text(last),
                                      last.to + 1, passes_in_window(passed, attempt, rule.window)));
    }
  }
  return p;
}

}  // namespace palpa::report
