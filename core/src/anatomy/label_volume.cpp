#include "palpa/anatomy/label_volume.hpp"

namespace palpa::anatomy {

std::array<double, 3> LabelVolume::world(double i, double j, double k) const {
  const double a[3] = {spacing[0] * i, spacing[1] * j, spacing[2] * k};
  std::array<double, 3> p = origin;
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) p[r] += direction[3 * r + c] * a[c];
  }
  return p;
}

}  // namespace palpa::anatomy
