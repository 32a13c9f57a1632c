#include "palpa/author/problem_text.hpp"

#include <cmath>
// GCC 12's -Wmaybe-uninitialized misfires inside libstdc++'s <regex> (std::function moves
// in the NFA builder) at -O1 with the sanitizers (the dev preset): a known false positive,
// silenced for the header only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop
#else
#include <regex>
#endif

#include <fmt/format.h>

namespace palpa::author {
namespace {

// A length or modulus as the window shows it: three significant digits ("26.1", "40").
// Three significant digits ("26.1", "40"), whole numbers from 1000 on ("20000", not "2e+04").
std::string shown(double x) { return std::abs(x) >= 1000.0 ? fmt::format("{:.0f}", x) : fmt::format("{:.3g}", x); }

std::string capitalized(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

// The scoring keys by what the window calls them.
std::string scoring_label(const std::string& key) {
  static const std::pair<const char*, const char*> kLabels[] = {
      {"min_coverage", "minimum coverage"},        {"min_deep_coverage", "minimum deep coverage"},
      {"max_force", "maximum force"},              {"hit_margin", "hit margin"},
      {"light_max", "light pressure up to"},       {"deep_min", "deep pressure from"},
      {"min_duration", "minimum duration"},        {"max_false_positives", "false marks allowed"},
  };
  for (const auto& [k, label] : kLabels) {
    if (key == k) return label;
  }
  return key;
}

// "tumour (radius R m) is not inside body "B": it reaches X m beyond the surface" and
// "... its centre is X m outside the surface" (scene::Scene::build).
bool describe_outside(const std::string& reason, AuthorProblem& out) {
  static const std::regex kOutside(
      R"(tumour \(radius ([-+0-9.eE]+) m\) is not inside body "[^"]*": (it reaches|its centre is) ([-+0-9.eE]+) m (beyond|outside) the surface)");
  std::smatch m;
  if (!std::regex_search(reason, m, kOutside)) return false;
  const double radius = std::stod(m[1].str()) * 1e3, by = std::stod(m[3].str()) * 1e3;
  const std::string row = fmt::format("Tumour {}", *out.tumour + 1);
  if (m[2].str() == "it reaches") {
    // The centre is inside: the sphere is too large for where it is.
    out.field = ProblemField::Radius;
    out.text = fmt::format("{}, radius: {} mm reaches {} mm beyond the skin", row, shown(radius), shown(by));
  } else {
    out.field = ProblemField::Depth;
    // The centre itself is out (above the skin, or below the base): the depth is at fault.
    out.text = fmt::format("{}, depth: its centre is outside the body (the tumour reaches {} mm beyond the surface)",
                           row, shown(by));
  }
  return true;
}

ProblemField tumour_field(const std::string& rest) {
  if (rest.rfind("radius", 0) == 0) return ProblemField::Radius;
  if (rest.rfind("stiffness", 0) == 0 || rest.rfind("modulus", 0) == 0 || rest.rfind("stiffening", 0) == 0) {
    return ProblemField::Material;
  }
  if (rest.rfind("center", 0) == 0 || rest.rfind("anchor", 0) == 0) return ProblemField::Depth;
  if (rest.rfind("placement", 0) == 0) return ProblemField::Placement;
  if (rest.rfind("body", 0) == 0) return ProblemField::TumourBody;
  return ProblemField::None;
}

std::string field_name(ProblemField f, const std::string& rest) {
  switch (f) {
    case ProblemField::Radius: return "radius";
    case ProblemField::Material: return rest.rfind("stiffening", 0) == 0 ? "stiffening" : "material";
    case ProblemField::Depth: return "depth";
    case ProblemField::Placement: return "random placement";
    case ProblemField::TumourBody: return "body";
    default: return {};
  }
}

// The rule's u, v and depth are shares: named as the window names them.
std::string placement_words(std::string reason) {
  static const std::regex kU(R"(^u\b)"), kV(R"(^v\b)"), kDepth(R"(^depth\b)");
  reason = std::regex_replace(reason, kU, "along x");
  reason = std::regex_replace(reason, kV, "along y");
  return std::regex_replace(reason, kDepth, "random depth (share of the thickness)");
}

// "radius 0.06 m is outside ..." under "Tumour 1, radius:" reads without its first word.
std::string without_key(const std::string& where, const std::string& reason) {
  const std::string key = where.substr(where.rfind('/') + 1);
  if (!key.empty() && reason.rfind(key + " ", 0) == 0) return reason.substr(key.size() + 1);
  return reason;
}

// A number as a percentage ("0.55" -> "55").
std::string percent(const std::string& share) { return shown(std::stod(share) * 100.0); }

// A scoring problem's reason in the window's words: shares in %, the keys by their labels.
std::string scoring_words(const std::string& key, std::string reason) {
  static const std::regex kBare(R"(^([-+0-9.eE]+) is outside (.*\] (m|Pa))$)");
  static const std::regex kShare(R"(^([-+0-9.eE]+) is outside \[0, 1\]$)");
  static const std::regex kBands(R"(^light_max ([-+0-9.eE]+) must be below deep_min ([-+0-9.eE]+)(.*)$)");
  const bool in_percent = key == "min_coverage" || key == "min_deep_coverage" || key == "light_max" || key == "deep_min";
  std::smatch m;
  if (in_percent && std::regex_match(reason, m, kShare)) return percent(m[1].str()) + " % is outside [0, 100] %";
  if (std::regex_match(reason, m, kBands)) {
    return "light pressure up to " + percent(m[1].str()) + " % must be below deep pressure from " +
           percent(m[2].str()) + " %" + m[3].str();
  }
  // "2 is outside (0, 1] m": the value is in the range's unit too.
  return std::regex_replace(reason, kBare, "$1 $3 is outside $2");
}

}  // namespace

std::string si_to_instructor_units(const std::string& text) {
  static const std::regex kNumber(R"(([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?) (m|Pa)\b)");
  static const std::regex kRange(R"(([\[(])([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?), ([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)([\])]) (m|Pa)\b)");
  std::string out;
  // Ranges first ("(0, 0.05] m"): both ends take the unit.
  std::string rest = text;
  for (std::smatch m; std::regex_search(rest, m, kRange); rest = m.suffix().str()) {
    const double scale = m[5].str() == "m" ? 1e3 : 1e-3;
    out += m.prefix().str() + m[1].str() + shown(std::stod(m[2].str()) * scale) + ", " +
           shown(std::stod(m[3].str()) * scale) + m[4].str() + (m[5].str() == "m" ? " mm" : " kPa");
  }
  out += rest;
  std::string result;
  rest = out;
  for (std::smatch m; std::regex_search(rest, m, kNumber); rest = m.suffix().str()) {
    const bool metres = m[2].str() == "m";
    result += m.prefix().str() + shown(std::stod(m[1].str()) * (metres ? 1e3 : 1e-3)) + (metres ? " mm" : " kPa");
  }
  return result + rest;
}

AuthorProblem describe(const io::Problem& problem) {
  AuthorProblem out;
  out.where = problem.where;
  const std::string& w = problem.where;
  static const std::regex kTumour(R"(^/tumors/([0-9]+)(?:/(.*))?$)");
  std::smatch m;
  if (std::regex_match(w, m, kTumour)) {
    out.tumour = static_cast<std::size_t>(std::stoull(m[1].str()));
    const std::string rest = m[2].matched ? m[2].str() : std::string();
    if (rest.empty() && describe_outside(problem.reason, out)) return out;
    out.field = tumour_field(rest);
    const std::string reason =
        out.field == ProblemField::Placement ? placement_words(problem.reason) : without_key(w, problem.reason);
    const std::string name = field_name(out.field, rest);
    out.text = fmt::format("Tumour {}{}: {}", *out.tumour + 1, name.empty() ? "" : ", " + name,
                           si_to_instructor_units(reason));
    return out;
  }
  std::string label;
  if (w.rfind("/bodies", 0) == 0 || w.rfind("/preset", 0) == 0) {
    out.field = ProblemField::Body;
    label = "Body";
  } else if (w.rfind("/title", 0) == 0) {
    out.field = ProblemField::Title;
    label = "Title";
  } else if (w.rfind("/description", 0) == 0) {
    out.field = ProblemField::Description;
    label = "Description";
  } else if (w.rfind("/scoring", 0) == 0) {
    out.field = ProblemField::Scoring;
    out.key = w.size() > 9 ? w.substr(9) : std::string();
    label = out.key.empty() ? "Scoring" : "Scoring, " + scoring_label(out.key);
  } else if (w.rfind("/exam_region", 0) == 0) {
    out.field = ProblemField::ExamRegion;
    label = "Exam region";
  }
  std::string reason = out.field == ProblemField::Scoring ? without_key(w, problem.reason) : problem.reason;
  if (out.field == ProblemField::Scoring) reason = scoring_words(out.key, reason);
  reason = si_to_instructor_units(reason);
  out.text = label.empty() ? capitalized(reason) : label + ": " + reason;
  return out;
}

std::vector<AuthorProblem> describe(const std::vector<io::Problem>& problems) {
  std::vector<AuthorProblem> out;
  out.reserve(problems.size());
  for (const auto& p : problems) out.push_back(describe(p));
  return out;
}

std::vector<AuthorProblem> palpability_warnings(const std::vector<TumourPalpability>& checked) {
  std::vector<AuthorProblem> out;
  for (const auto& c : checked) {
    if (c.palpable) continue;
    AuthorProblem w;
    w.where = fmt::format("/tumors/{}", c.tumour);
    w.tumour = c.tumour;
    w.warning = true;
    const long raise = std::lround((c.contrast - 1.0) * 100.0);
    const long needs = std::lround((kPalpableContrast - 1.0) * 100.0);
    w.text = fmt::format("Tumour {} may not be palpable: at deep pressure it raises the force by {} % (the scripted "
                         "expert needs about {} %)",
                         c.tumour + 1, raise, needs);
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace palpa::author
