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

std::map<Label, std::size_t> label_counts(const LabelVolume& volume) {
  std::map<Label, std::size_t> counts;
  std::size_t at = 0;
  while (at < volume.labels.size()) {
    const Label label = volume.labels[at];
    std::size_t end = at + 1;
    while (end < volume.labels.size() && volume.labels[end] == label) ++end;
    counts[label] += end - at;
    at = end;
  }
  return counts;
}

}  // namespace palpa::anatomy
