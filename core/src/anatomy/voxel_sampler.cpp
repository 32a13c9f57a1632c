#include "voxel_sampler.hpp"

#include <cmath>

namespace palpa::anatomy {

VoxelSampler::VoxelSampler(const LabelVolume& volume, const LabelTable& table) : volume_(volume) {
  // The table's labels span at most kMaxLabelSpan values (parse_label_table): the dense
  // array stays small whatever the labels' signs.
  if (!table.labels.empty()) {
    first_ = table.labels.begin()->first;
    const auto span = static_cast<std::size_t>(static_cast<std::int64_t>(table.labels.rbegin()->first) - first_ + 1);
    classes_.assign(span, LabelClass::Outside);
    for (const auto& [label, entry] : table.labels) classes_[static_cast<std::size_t>(label - first_)] = entry.kind;
  }
  Eigen::Matrix3d d;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) d(r, c) = volume.direction[static_cast<std::size_t>(3 * r + c)];
  }
  const Eigen::Vector3d spacing(volume.spacing[0], volume.spacing[1], volume.spacing[2]);
  // world = origin + D diag(spacing) index, D orthonormal: index = diag(1/spacing) D^T (world - origin).
  to_index_ = spacing.cwiseInverse().asDiagonal() * d.transpose();
  origin_ = to_vec3(volume.origin);
}

LabelClass VoxelSampler::at(int i, int j, int k) const {
  if (i < 0 || j < 0 || k < 0 || i >= volume_.dims[0] || j >= volume_.dims[1] || k >= volume_.dims[2]) {
    return LabelClass::Outside;
  }
  return class_of(volume_.labels[volume_.index(i, j, k)]);
}

LabelClass VoxelSampler::nearest(const Vec3& x) const {
  return at(static_cast<int>(std::lround(x.x())), static_cast<int>(std::lround(x.y())),
            static_cast<int>(std::lround(x.z())));
}

std::optional<Label> VoxelSampler::nearest_label(const Vec3& x) const {
  const int i = static_cast<int>(std::lround(x.x())), j = static_cast<int>(std::lround(x.y())),
            k = static_cast<int>(std::lround(x.z()));
  if (i < 0 || j < 0 || k < 0 || i >= volume_.dims[0] || j >= volume_.dims[1] || k >= volume_.dims[2]) {
    return std::nullopt;
  }
  return volume_.labels[volume_.index(i, j, k)];
}

double VoxelSampler::share(const Vec3& x, bool (*member)(LabelClass)) const {
  const int i = static_cast<int>(std::floor(x.x())), j = static_cast<int>(std::floor(x.y())),
            k = static_cast<int>(std::floor(x.z()));
  const double fx = x.x() - i, fy = x.y() - j, fz = x.z() - k;
  double sum = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double w = (di ? fx : 1.0 - fx) * (dj ? fy : 1.0 - fy) * (dk ? fz : 1.0 - fz);
    if (w > 0.0 && member(at(i + di, j + dj, k + dk))) sum += w;
  }
  return sum;
}

}  // namespace palpa::anatomy
