#pragma once
// The validation problems of a case (io::Problem: a JSON pointer and a reason in SI units,
// as palpa-cli validate prints them) in the instructor's terms: the tumour by its row in
// the window's table (1-based), the field at fault by the name of its control, lengths in
// mm and moduli in kPa ("Tumour 2, radius: 40 mm reaches 26.1 mm beyond the skin").
// palpa-cli keeps its own messages; this is a translation for the authoring window.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "palpa/author/palpability.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::author {

/// The control a problem is about.
enum class ProblemField {
  None,       ///< the case as a whole
  Title,
  Description,
  Body,       ///< the body (preset) controls
  Depth,      ///< a tumour's depth below the skin (its centre)
  Radius,
  Material,   ///< stiffness, modulus or stiffening
  Placement,  ///< the randomization rule
  TumourBody, ///< the body a tumour names
  Scoring,    ///< a scoring threshold (`key` names it)
  ExamRegion,
};

struct AuthorProblem {
  std::string where;                  ///< the JSON pointer, as io::Problem gives it
  std::optional<std::size_t> tumour;  ///< index into "tumors" (shown as index + 1)
  ProblemField field = ProblemField::None;
  std::string key;                    ///< the scoring key, for ProblemField::Scoring
  std::string text;                   ///< for the instructor
  bool warning = false;               ///< true: the case is valid all the same
};

/// `problem` in the instructor's terms.
AuthorProblem describe(const io::Problem& problem);
std::vector<AuthorProblem> describe(const std::vector<io::Problem>& problems);

/// A warning for each tumour that is likely not palpable ("Tumour 2 may not be palpable: at
/// deep pressure it raises the force by 6 % (the scripted expert needs 15 %)").
std::vector<AuthorProblem> palpability_warnings(const std::vector<TumourPalpability>& checked);

/// "0.02614 m" -> "26.1 mm", "6480 Pa" -> "6.48 kPa", "[0, 0.05] m" -> "[0, 50] mm" in any text.
std::string si_to_instructor_units(const std::string& text);

}  // namespace palpa::author
