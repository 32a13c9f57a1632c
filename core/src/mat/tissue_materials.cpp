#include "palpa/mat/tissue_materials.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace palpa::mat {
namespace {

// Krouskop et al. 1998 (Ultrasonic Imaging 20: 260-274), tangent moduli of breast samples
// at 5 % and 20 % pre-compression (kPa): glandular 28 and 48, invasive ductal carcinoma 106
// and 558. Fat's modulus was constant over the strains tested, so fat does not stiffen.
constexpr double kGlandular5 = 28.0, kGlandular20 = 48.0;
constexpr double kCarcinoma5 = 106.0, kCarcinoma20 = 558.0;

// Samani et al. 2007 (Phys. Med. Biol. 52: 1565-1576), small-strain moduli: fat 3.25 kPa,
// fibroglandular 3.24 kPa; fibroadenoma about twice that; invasive carcinoma 3-6 times,
// high-grade invasive ductal carcinoma up to 13 times.
constexpr double kFat = 3.25e3, kFibroglandular = 3.24e3;

const std::array<TissueMaterial, 5>& table() {
  static const std::array<TissueMaterial, 5> materials{{
      {"fat", "Breast fat", kFat, 0.0, false},
      {"fibroglandular", "Fibroglandular tissue", kFibroglandular, stiffening_between(kGlandular5, kGlandular20), false},
      {"fibroadenoma", "Fibroadenoma (benign)", 2.0 * kFibroglandular, 0.0, true},
      {"carcinoma", "Invasive ductal carcinoma", 6.0 * kFibroglandular, stiffening_between(kCarcinoma5, kCarcinoma20),
       true},
      {"carcinoma-high-grade", "High-grade invasive ductal carcinoma", 13.0 * kFibroglandular,
       stiffening_between(kCarcinoma5, kCarcinoma20), true},
  }};
  return materials;
}

}  // namespace

double stiffening_between(double e_low, double e_high, double eps_low, double eps_high) {
  if (!(e_low > 0.0) || !(e_high > 0.0) || !(eps_high > eps_low)) {
    throw std::invalid_argument("stiffening_between needs two positive moduli at increasing strains");
  }
  return std::log(e_high / e_low) / (eps_high - eps_low);
}

std::span<const TissueMaterial> tissue_materials() { return table(); }

const TissueMaterial* find_tissue_material(std::string_view key) {
  for (const auto& m : table()) {
    if (m.key == key) return &m;
  }
  return nullptr;
}

}  // namespace palpa::mat
