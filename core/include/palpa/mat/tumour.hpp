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
};

}  // namespace palpa::mat
