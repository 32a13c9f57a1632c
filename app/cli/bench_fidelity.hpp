#pragma once
// palpa-cli bench fidelity: Palpa's forces against the finite-element reference curves
// (data/reference): force-depth error of the calibrated law and of the paper's law, on the
// reference's layer given in Pa, at each depth the reference reached; and the tumour
// contrast of every inclusion of the on-axis sweep.
#include <filesystem>

namespace palpa::cli {

/// Reads the curves in `reference_dir`, writes fidelity.csv, fidelity_contrast.csv and
/// fidelity.png into out_dir, prints summary tables. 0 when the calibrated law is within 10 %
/// of every force curve and within 20 % of C - 1 (or 0.02) on every inclusion, 1 when it is
/// not, 2 when a curve cannot be read (one line naming the file).
int run_bench_fidelity(const std::filesystem::path& reference_dir, const std::filesystem::path& out_dir);

}  // namespace palpa::cli
