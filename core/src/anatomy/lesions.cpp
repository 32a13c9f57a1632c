// Lesions from a label volume: each 6-connected component of a lesion label, measured by
// its centroid and the radius of the sphere of its volume (docs/anatomy-import.md).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "palpa/anatomy/import.hpp"
#include "voxel_sampler.hpp"

namespace palpa::anatomy {

namespace {

struct Component {
  std::size_t voxels = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();  // of voxel indices
};

// Flood fill from `seed` over voxels holding `label`, with an explicit stack (a lesion of
// millions of voxels must not overflow the call stack); `seen` marks what was taken.
Component flood(const LabelVolume& v, std::size_t seed, Label label, std::vector<bool>& seen) {
  Component c;
  std::vector<std::size_t> stack{seed};
  seen[seed] = true;
  const auto nx = static_cast<std::size_t>(v.dims[0]), ny = static_cast<std::size_t>(v.dims[1]),
             nz = static_cast<std::size_t>(v.dims[2]);
  while (!stack.empty()) {
    const std::size_t at = stack.back();
    stack.pop_back();
    const std::size_t i = at % nx, j = at / nx % ny, k = at / (nx * ny);
    ++c.voxels;
    c.sum += Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
    const auto visit = [&](bool inside, std::size_t next) {
      if (inside && !seen[next] && v.labels[next] == label) {
        seen[next] = true;
        stack.push_back(next);
      }
    };
    visit(i > 0, at - 1);
    visit(i + 1 < nx, at + 1);
    visit(j > 0, at - nx);
    visit(j + 1 < ny, at + nx);
    visit(k > 0, at - nx * ny);
    visit(k + 1 < nz, at + nx * ny);
  }
  return c;
}

}  // namespace

std::vector<Lesion> find_lesions(const LabelVolume& volume, const LabelTable& table) {
  // Labels come in runs: the table is asked again only when the label changes.
  Label last = 0;
  bool last_is = false, asked = false;
  auto is_lesion = [&](Label label) {
    if (!asked || label != last) {
      const LabelEntry* entry = table.find(label);
      last = label;
      last_is = entry != nullptr && entry->kind == LabelClass::Lesion;
      asked = true;
    }
    return last_is;
  };
  std::vector<bool> seen(volume.labels.size(), false);
  std::vector<Lesion> out;
  const double voxel_volume = volume.spacing[0] * volume.spacing[1] * volume.spacing[2];
  for (std::size_t at = 0; at < volume.labels.size(); ++at) {
    if (seen[at] || !is_lesion(volume.labels[at])) continue;
    const Component c = flood(volume, at, volume.labels[at], seen);
    const LabelEntry& entry = *table.find(volume.labels[at]);
    const Eigen::Vector3d mean = c.sum / static_cast<double>(c.voxels);
    Lesion lesion;
    lesion.label = volume.labels[at];
    lesion.name = entry.name.empty() ? "lesion" : entry.name;
    lesion.voxels = c.voxels;
    lesion.centre = to_vec3(volume.world(mean.x(), mean.y(), mean.z()));
    lesion.radius = std::cbrt(3.0 * static_cast<double>(c.voxels) * voxel_volume / (4.0 * std::numbers::pi));
    lesion.modulus = entry.modulus;
    lesion.stiffening = entry.stiffening;
    out.push_back(std::move(lesion));
  }
  std::stable_sort(out.begin(), out.end(), [](const Lesion& a, const Lesion& b) { return a.voxels > b.voxels; });
  return out;
}

}  // namespace palpa::anatomy
