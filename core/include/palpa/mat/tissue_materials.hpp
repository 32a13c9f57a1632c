#pragma once
// Breast tissues in the units a case is written in (docs/case-authoring.md, "Tissue
// materials"): the small-strain Young's modulus of Samani, Zubovits and Plewes (2007) and
// the strain stiffening b of E_t(eps) = E exp(b eps) from Krouskop et al. (1998).
#include <span>
#include <string_view>

namespace palpa::mat {

struct TissueMaterial {
  std::string_view key;   ///< stable name for files and options, e.g. "fibroglandular"
  std::string_view name;  ///< for people
  double modulus;         ///< Pa, at small strain
  double stiffening;      ///< b (per unit strain); 0: no stiffening measured
  bool tumour;            ///< a mass (tumour modulus) rather than a body's tissue
};

/// b of E_t(eps) = E exp(b eps) through two tangent moduli: e_low at strain eps_low and
/// e_high at eps_high (Krouskop's 5 % and 20 % pre-compression by default).
double stiffening_between(double e_low, double e_high, double eps_low = 0.05, double eps_high = 0.20);

/// The bundled materials: body tissues first, then masses.
std::span<const TissueMaterial> tissue_materials();

/// The material called `key`; nullptr if there is none.
const TissueMaterial* find_tissue_material(std::string_view key);

}  // namespace palpa::mat
