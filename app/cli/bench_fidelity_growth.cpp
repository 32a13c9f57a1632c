#include "bench_fidelity_growth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "bench_fidelity_contrast.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::cli::fidelity {
namespace {

struct TwinFiles {
  const char* stiff;  // the 5x inclusion
  const char* plain;  // its 1x twin, the same mesh
  double thickness, radius, depth, ratio;
  mat::Indenter indenter = mat::Indenter::Pad;
};
constexpr TwinFiles kTwins[] = {
    {"slab40_E5k_flat_neohooke_pinned_incl5x.csv", "slab40_E5k_flat_neohooke_pinned_incl1x.csv", 0.040, 0.005, 0.010,
     5.0},
    {"slab40_E5k_flat_neohooke_pinned_r10d20_incl5x.csv", "slab40_E5k_flat_neohooke_pinned_r10d20_incl1x.csv", 0.040,
     0.010, 0.020, 5.0},
    {"slab20_E5k_flat_neohooke_pinned_incl5x.csv", "slab20_E5k_flat_neohooke_pinned_incl1x.csv", 0.020, 0.005, 0.010,
     5.0},
    // The rounded finger's contrast: the pad's model read as the finger's contact acts
    // (contact::TumourContrast::Finger, docs/model.md, "A tumour under the rounded finger").
    {"slab40_E5k_finger8_neohooke_incl5x.csv", "slab40_E5k_finger8_neohooke_incl1x.csv", 0.040, 0.005, 0.010, 5.0,
     mat::Indenter::Finger},
    {"slab40_E5k_finger8_neohooke_r10d20_incl5x.csv", "slab40_E5k_finger8_neohooke_r10d20_incl1x.csv", 0.040, 0.010,
     0.020, 5.0, mat::Indenter::Finger},
    {"slab20_E5k_finger8_neohooke_incl5x.csv", "slab20_E5k_finger8_neohooke_incl1x.csv", 0.020, 0.005, 0.010, 5.0,
     mat::Indenter::Finger},
};

Growth compare(const TwinFiles& t, const std::filesystem::path& reference_dir) {
  const auto stiff = read_force_curve(reference_dir / t.stiff);
  const auto plain = read_force_curve(reference_dir / t.plain);
  Inclusion inclusion{t.thickness, t.radius, t.depth, t.ratio};
  inclusion.indenter = t.indenter;
  const auto with = with_tumour(inclusion, mat::ForceModel::Calibrated, 0.0);
  const auto without = plain_slab(t.thickness, mat::ForceModel::Calibrated, t.indenter);
  Growth g;
  g.finger = t.indenter == mat::Indenter::Finger;
  const std::size_t n = std::min(stiff.size(), plain.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (stiff[k][0] != plain[k][0]) {
      throw std::runtime_error(fmt::format("{}: row {}: depth differs from {}", t.stiff, k + 2, t.plain));
    }
    const double d = stiff[k][0];
    GrowthRow r{t.thickness, t.radius, t.depth, t.ratio, d, stiff[k][1] / plain[k][1],
                centre_force(with, d) / centre_force(without, d)};
    if (g.fem_onset < 0.0 && r.fem >= kOnsetContrast) g.fem_onset = d;
    g.rows.push_back(r);
  }
  g.calibrated_onset = onset(with, without, g.rows.back().press);
  return g;
}

}  // namespace

std::vector<Growth> contrast_growth(const std::filesystem::path& reference_dir) {
  std::vector<Growth> twins;
  for (const auto& t : kTwins) twins.push_back(compare(t, reference_dir));
  return twins;
}

void write_growth_csv(const std::vector<Growth>& twins, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "thickness_m,inclusion_radius_m,inclusion_depth_m,modulus_ratio,press_m,fem_contrast,calibrated_contrast,"
         "indenter\n";
  for (const auto& g : twins) {
    for (const auto& r : g.rows) {
      out << fmt::format("{:.3f},{:.4f},{:.4f},{:g},{:.5f},{:.5f},{:.5f},{}\n", r.thickness, r.radius, r.depth, r.ratio,
                         r.press, r.fem, r.calibrated, g.finger ? "finger" : "pad");
    }
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace palpa::cli::fidelity
