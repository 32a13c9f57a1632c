#pragma once
// Internal to core/anatomy: a label volume read at world points, by class.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

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
  /// The label of the voxel nearest to x; none beyond the volume.
  std::optional<Label> nearest_label(const Vec3& x) const;
  /// The share (0..1) of the 8 voxels around x, weighted trilinearly, whose class
  /// `member` accepts: the segmentation's smooth indicator, its 0.5 level the surface.
  double share(const Vec3& x, bool (*member)(LabelClass)) const;
  /// The class of a label; Outside for a label the table does not list.
  LabelClass class_of(Label label) const {
    const auto at = static_cast<std::int64_t>(label) - first_;
    return at >= 0 && at < static_cast<std::int64_t>(classes_.size()) ? classes_[static_cast<std::size_t>(at)]
                                                                        : LabelClass::Outside;
  }
  const LabelVolume& volume() const { return volume_; }

 private:
  LabelClass at(int i, int j, int k) const;

  const LabelVolume& volume_;
  // The classes of the labels from first_ on, densely (a lookup per voxel read).
  std::int64_t first_ = 0;
  std::vector<LabelClass> classes_;
  Eigen::Matrix3d to_index_;
  Vec3 origin_;
};

}  // namespace palpa::anatomy
