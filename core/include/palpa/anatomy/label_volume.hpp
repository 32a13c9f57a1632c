#pragma once
// A segmented image as the import sees it (docs/anatomy-import.md): one integer label per
// voxel and the voxel grid's place in the world. Plain arrays, no VTK: the readers
// (readers/) fill it from NIfTI, NRRD, MetaImage or VTK image files.
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace palpa::anatomy {

/// A voxel's label: any integer a segmentation tool writes, negative ones included
/// (patient MRI models label lesions -4 and -3, skin -2, muscle -1).
using Label = std::int32_t;

/// World coordinates are RAS, the frame of NIfTI and 3D Slicer: +x towards the patient's
/// right, +y anterior, +z superior (docs/anatomy-import.md, "Coordinates"); a reader of an
/// LPS file (MetaImage, NRRD in LPS) turns it into RAS.
struct LabelVolume {
  std::array<int, 3> dims{};        ///< voxels along the index axes i, j, k
  std::array<double, 3> spacing{};  ///< m between voxel centres along i, j, k
  std::array<double, 3> origin{};   ///< m: the world (RAS) position of voxel (0, 0, 0)'s centre
  /// Row-major 3 x 3: column c is the unit world direction of index axis c, so that
  /// world(i, j, k) = origin + direction * (spacing[0] i, spacing[1] j, spacing[2] k).
  std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};
  /// One label per voxel, i fastest: voxel (i, j, k) at i + dims[0] * (j + dims[1] * k).
  std::vector<Label> labels;

  std::size_t voxel_count() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(dims[2]);
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims[0]) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(k));
  }
  /// World position (m) of voxel (i, j, k)'s centre (fractional indices allowed).
  std::array<double, 3> world(double i, double j, double k) const;
};

/// The most voxels a volume may claim (2^27, e.g. 512^3): checked from the header before
/// anything is allocated; 4 bytes a voxel here and about as much in the reader.
inline constexpr std::size_t kMaxVoxels = std::size_t{1} << 27;

/// How many voxels hold each label (one pass; runs of one label counted at once).
std::map<Label, std::size_t> label_counts(const LabelVolume& volume);

}  // namespace palpa::anatomy
