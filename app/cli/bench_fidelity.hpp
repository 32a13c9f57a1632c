#pragma once
// palpa-cli bench fidelity: Palpa's forces against the finite-element reference curves
// (data/reference): force-depth error of the calibrated law and of the paper's law, on the
// reference's layer given in Pa, at each depth the reference reached; the tumour contrast
// and its onset depth for every inclusion of the on-axis sweeps (20, 30 and 40 mm layers);
// and the contrast beside the pad's axis with its lateral half-width (3-D sweep, 40 mm).
#include <filesystem>

namespace palpa::cli {

/// Reads the curves in `reference_dir`, writes fidelity.csv, fidelity_contrast.csv,
/// fidelity_lateral.csv and fidelity.png into out_dir, prints summary tables. 0 when the
/// calibrated law is within 10 % of every force curve, within 20 % of C - 1 (or 0.02) on
/// every inclusion, its onset within 2 mm and its lateral half-width within 3 mm of the
/// FEM's; 1 when it is not, 2 when a curve cannot be read (one line naming the file).
int run_bench_fidelity(const std::filesystem::path& reference_dir, const std::filesystem::path& out_dir);

}  // namespace palpa::cli
