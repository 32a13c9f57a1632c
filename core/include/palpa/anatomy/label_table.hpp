#pragma once
// What each label of a segmentation is (docs/anatomy-import.md, "Label tables"): tissue
// the finger presses, skin, the rigid support the body rests on, a lesion that becomes a
// tumour, or outside the body. JSON:
//   {"labels": {"<integer label, any sign>": {"class": "tissue"|"skin"|"support"|"lesion"|"outside",
//                                  "name": "...", "modulus": <Pa>, "stiffening": <b>}}}
// with `modulus` required for tissue, skin and lesion, `stiffening` optional.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "palpa/anatomy/label_volume.hpp"

namespace palpa::anatomy {

enum class LabelClass : std::uint8_t { Outside, Tissue, Skin, Support, Lesion };
const char* to_string(LabelClass kind);

struct LabelEntry {
  LabelClass kind = LabelClass::Outside;
  std::string name;
  double modulus = 0.0;     ///< Pa; 0 for outside and support
  double stiffening = 0.0;  ///< b of E exp(b eps) (docs/model.md, "Strain stiffening")
};

struct LabelTable {
  std::string name;  ///< "victre", "generic", or the file's name
  std::map<Label, LabelEntry> labels;

  const LabelEntry* find(Label label) const;
  /// True for tissue, skin and lesion: what lies between the support and the air.
  static bool soft(LabelClass kind) { return kind == LabelClass::Tissue || kind == LabelClass::Skin || kind == LabelClass::Lesion; }
};

/// Limits on a label table file, checked before parsing.
inline constexpr std::size_t kMaxLabelTableBytes = 1u << 20;
inline constexpr std::size_t kMaxLabels = 4096;
inline constexpr std::size_t kMaxLabelNameLength = 64;
/// The labels of one table lie within this many consecutive integers (any sign): the
/// import looks classes up in an array over them.
inline constexpr std::size_t kMaxLabelSpan = std::size_t{1} << 20;

/// Parses a label table; `source` names it in errors. Throws ImportError with one line
/// "SOURCE: /labels/KEY/FIELD: what is wrong".
LabelTable parse_label_table(std::string_view text, const std::string& source);

/// The built-in tables: "victre" (the VICTRE breast phantom's labels with moduli from the
/// literature) and "generic" (0 outside, 1 tissue, 2 skin, 3 support, 4 lesion).
/// Throws ImportError for another name.
LabelTable builtin_label_table(std::string_view name);
std::vector<std::string> builtin_label_table_names();

}  // namespace palpa::anatomy
