#pragma once
// Whether the tumours of a valid case can be felt: for each tumour, the force the model
// gives at deep pressure over it against the force at the same indentation where the
// tissue has no tumour (docs/case-authoring.md, "Palpability"). A tumour whose contrast is
// below what the scripted expert notices is likely missed by a trainee too: the
// instructor window warns about it (the case stays valid).
#include <cstddef>
#include <string>
#include <vector>

#include "palpa/io/case_file.hpp"

namespace palpa::author {

/// The contrast the scripted expert needs to find a tumour, measured by running it over
/// the whole breast (tissue in Pa and in N/m) on one tumour at a time: it missed every tumour
/// up to 1.212 and found every one from 1.25 on; in between it found 3 of 5 (BENCHMARKS.md).
/// Warning below 1.25, no tumour it missed goes without a warning. Its own
/// thresholds compare a spot with its neighbourhood's median (suspicion at 1.2 in Pa, 1.3
/// in N/m), which the tumour lifts too, so it needs more than they say over plain tissue.
/// (kFeltSpotRatio, 1.15, is what a search press may have felt, not what it finds.)
inline constexpr double kPalpableContrast = 1.25;

struct TumourPalpability {
  std::size_t tumour = 0;       ///< index into the case's tumours
  double indentation = 0.0;     ///< m: the deep press, straight over the tumour's centre
  double thickness = 0.0;       ///< m: the tissue's thickness there (2R)
  double force = 0.0;           ///< N: |F| there with the tumours
  double plain_force = 0.0;     ///< N: |F| at the same point without them
  /// force / plain_force: 1.06 means the tumour raises the force by 6 %.
  double contrast = 0.0;
  bool palpable = true;         ///< contrast >= kPalpableContrast
};

/// The deep press of the scripted expert, as a share of the local thickness.
double deep_press_share();

/// Each tumour of `file` as written (a randomized tumour where the case writes it). `file`
/// must be valid (CaseDraft::valid_case); throws io::CaseError otherwise.
std::vector<TumourPalpability> check_palpability(const io::CaseFile& file, const std::string& source);

}  // namespace palpa::author
