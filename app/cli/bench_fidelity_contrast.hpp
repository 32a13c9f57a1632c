#pragma once
// palpa-cli bench fidelity, tumour contrast: Palpa's F_with / F_without against the
// finite-element sweeps of data/reference: on the pad's axis for layers of 20, 30 and 40 mm
// (with the onset depth, the first press at which the contrast reaches 1.10), and beside
// the axis on the 40 mm layer (with the lateral half-width of the extra force).
#include <array>
#include <filesystem>
#include <vector>

#include "palpa/scene/scene.hpp"

namespace palpa::cli::fidelity {

inline constexpr double kSlabWidth = 0.12;       ///< m: the 60 mm-radius disc stands in for a 120 mm slab
inline constexpr double kLayerModulus = 5000.0;  ///< Pa: every reference layer's
inline constexpr double kOnsetContrast = 1.10;   ///< the contrast a trainee is taken to notice

/// |F| (N) of a press `depth` straight down into the middle of a slab's top, as the engine
/// probes (by default its default options: shear springs requested, followed where the law
/// has them).
double centre_force(const scene::Scene& scene, double depth, const scene::ProbeOptions& options = {});

/// The "depth_m,force_n" rows of a reference curve above 0 depth. Throws
/// std::runtime_error naming the file and line it cannot read.
std::vector<std::array<double, 2>> read_force_curve(const std::filesystem::path& path);

/// One inclusion: a stiff sphere of radius r, centre s below the skin, modulus q times the
/// layer's, `offset` beside the pad's axis, in a layer of 5 kPa and thickness h.
struct Inclusion {
  double thickness = 0.0, radius = 0.0, depth = 0.0, ratio = 0.0, offset = 0.0;  // m, m, m, -, m
  double fem = 0.0;         // the FEM's contrast
  double calibrated = 0.0;  // Palpa, the tumour in Pa, at a 2 mm press in the small-strain limit
  double paper = 0.0;       // the paper's law, a tumour spring of 0.02 m x E_t, at a 4 mm press
  // First press depth (m) with contrast >= 1.10, or a negative value when none reaches it
  // up to 40 % of the thickness (the FEM's: linear, so at first touch or never).
  double fem_onset = -1.0, calibrated_onset = -1.0, paper_onset = -1.0;
  mat::Indenter indenter = mat::Indenter::Pad;  // what presses (the sweeps: the flat pad)
};

/// The 120 mm slab of 5 kPa of `inclusion`'s layer with its tumour: in Pa, or as a spring of
/// `stiffness` N/m when that is above 0; `offset` beside the slab's centre, along x.
scene::Scene with_tumour(const Inclusion& inclusion, mat::ForceModel law, double stiffness);

/// The 120 mm slab of 5 kPa and `thickness` (m) without a tumour, under `law`, pressed by `indenter`.
scene::Scene plain_slab(double thickness, mat::ForceModel law, mat::Indenter indenter = mat::Indenter::Pad);

/// The first press depth (m, in steps of 0.25 mm up to `reach`) at which `tumour` pushes back
/// kOnsetContrast times as hard as `plain`, as the engine probes with `options`; -1 if none.
double onset(const scene::Scene& tumour, const scene::Scene& plain, double reach,
             const scene::ProbeOptions& options = {});

/// The contrast mark: within 20 % of C - 1, or 0.02 where C - 1 is small.
bool contrast_met(double model, double fem);
/// The onset mark: both never reach 1.10, or both do within 2 mm of each other.
bool onset_met(double model, double fem);

/// The on-axis sweeps (contrast_slab{20,30,40}_E5k_linear.csv) with Palpa's values filled
/// in. Throws std::runtime_error naming a file and line it cannot read.
std::vector<Inclusion> on_axis(const std::filesystem::path& reference_dir);

/// The lateral sweep (lateral_slab40_E5k_linear.csv), Palpa's values at the same offsets.
std::vector<Inclusion> beside_axis(const std::filesystem::path& reference_dir);

/// Lateral half-width of one inclusion's extra force: the offset (m) at which C - 1 falls to
/// half its value on the axis, interpolated linearly between the rows (all of one inclusion,
/// by increasing offset); `which` picks the FEM's, the calibrated or the paper's contrast.
/// The last offset when it never halves there; -1 when nothing is felt on the axis.
enum class Source { Fem, Calibrated, Paper };
double half_width(const std::vector<Inclusion>& rows, Source which);

/// The rows of each inclusion of the lateral sweep, by increasing offset.
std::vector<std::vector<Inclusion>> by_inclusion(const std::vector<Inclusion>& rows);

void write_contrast_csv(const std::vector<Inclusion>& rows, const std::filesystem::path& path);
void write_lateral_csv(const std::vector<Inclusion>& rows, const std::filesystem::path& path);

}  // namespace palpa::cli::fidelity
