#pragma once
// Internal to core/anatomy: a label volume read at world points, by class.
#include <array>
#include <functional>

#include <Eigen/Core>

#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/label_volume.hpp"
#include "palpa/vec3.hpp"

namespace palpa::anatomy {

class VoxelSampler {
 public:
  VoxelSampler(const LabelVolume& volume, const LabelTable& table);

  /// Continuous voxel index of a world point (voxel centres at integers).
  Vec3 index_of(const Vec3& p) const { return to_index_ * (p - origin_); }
  /// The class of the voxel nearest to index position x; Outside beyond the volume.
  LabelClass nearest(const Vec3& x) const;
  /// The label (and its class's entry) of the voxel nearest to x; -1 beyond the volume.
  int nearest_label(const Vec3& x) const;
  /// The share (0..1) of the 8 voxels around x, weighted trilinearly, whose class
  /// `member` accepts: the segmentation's smooth indicator, its 0.5 level the surface.
  double share(const Vec3& x, bool (*member)(LabelClass)) const;
  LabelClass class_of(int label) const { return classes_[static_cast<std::size_t>(label)]; }
  const LabelVolume& volume() const { return volume_; }

 private:
  LabelClass at(int i, int j, int k) const;

  const LabelVolume& volume_;
  std::array<LabelClass, 65536> classes_{};
  Eigen::Matrix3d to_index_;
  Vec3 origin_;
};

}  // namespace palpa::anatomy
