#pragma once
// palpa-cli bench fidelity, contrast growth: Palpa's F_with / F_without at each press depth
// of the neo-Hookean inclusion twins of data/reference (a 5x inclusion and its 1x twin on
// one mesh, solved with geometric nonlinearity), where the contrast grows with the press.
#include <filesystem>
#include <vector>

namespace palpa::cli::fidelity {

struct GrowthRow {
  double thickness = 0.0, radius = 0.0, depth = 0.0, ratio = 0.0;  // m, m, m (centre below the skin), -
  double press = 0.0;       // m
  double fem = 0.0;         // the FEM's contrast at this press
  double calibrated = 0.0;  // Palpa's, the tumour in Pa
};

/// One twin pair: its rows by increasing press, and the onsets (first press with contrast
/// >= 1.10, or -1 when none reaches it within the twin's reach; Palpa's scanned as far).
struct Growth {
  std::vector<GrowthRow> rows;
  double fem_onset = -1.0, calibrated_onset = -1.0;
  bool finger = false;  // pressed by the rounded finger, not the flat pad
};

/// Every committed twin pair. Throws std::runtime_error naming a file it cannot read.
std::vector<Growth> contrast_growth(const std::filesystem::path& reference_dir);

void write_growth_csv(const std::vector<Growth>& twins, const std::filesystem::path& path);

}  // namespace palpa::cli::fidelity
