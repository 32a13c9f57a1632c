#pragma once
// A tumour as a case authors it: a stiffer sphere inside one body (SI units).
#include <array>
#include <string>

namespace palpa::mat {

struct Tumour {
  std::string body;                  ///< id of the body that holds it
  std::array<double, 3> center{};    ///< m
  double radius = 0.0;               ///< m
  double stiffness = 0.0;            ///< N/m: the spring the fingertip meets when it reaches the tumour
  /// Pa: its Young's modulus, for a tumour given in Pa (0: given by `stiffness`). Such a
  /// tumour is felt through the contrast model (contact/force.hpp, TumourContrast).
  double modulus = 0.0;
  /// b in E_t(eps) = E exp(b eps) for a tumour given in Pa (0: no stiffening of its own).
  double stiffening = 0.0;
  /// Its modulus over the tissue's around it, set when the scene is built (0: not in Pa).
  double modulus_ratio = 0.0;
};

}  // namespace palpa::mat
