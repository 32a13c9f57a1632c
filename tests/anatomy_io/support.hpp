#pragma once
// Helpers shared by the anatomy_io tests: a scratch directory, file patching, and the
// analytic label volume and icosphere the round trips write and read.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"

namespace palpa::anatomy_io::test {

namespace fs = std::filesystem;

class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

std::string read_bytes(const fs::path& file);
void write_bytes(const fs::path& file, const std::string& bytes);

/// A ball of label 3 (centre voxel (10, 12, 14), radius 6 voxels) in a 20 x 24 x 28 grid,
/// spacing 0.7 x 0.9 x 1.3 mm, an oblique direction and an origin off zero; voxel (3, 5, 7)
/// holds label 7. Axis vectors and origin are rounded to float in millimetres so that
/// NIfTI-1 (float32 header) carries them exactly too.
anatomy::LabelVolume oblique_ball();

/// The same voxels with the axes permuted and one reversed, and the direction and origin
/// that put every voxel at the same world position: B(nz-1-k, i, j) = A(i, j, k).
anatomy::LabelVolume permuted_flipped(const anatomy::LabelVolume& a);

/// The world position of the one voxel with `label` (fails the test when not exactly one).
std::array<double, 3> world_of_label(const anatomy::LabelVolume& v, anatomy::Label label);

/// The mean world position of the voxels with `label`.
std::array<double, 3> centroid_of_label(const anatomy::LabelVolume& v, anatomy::Label label);

/// An icosphere of radius 0.05 m: 42 points, 80 triangles.
anatomy::TriangleMesh icosphere();

/// A NIfTI-1 file written byte by byte: 4 x 5 x 6 uint8, pixdim 2, 3, 4 mm, pixdim[0] = qfac,
/// quaternion (0, 0, sin 45 deg) (a quarter turn about z), qoffset (10, 20, 30) mm, sform rows
/// (0 0 -2.5 7) (1.5 0 0 8) (0 3.5 0 9); voxel (1, 2, 3) labelled 5.
std::string nifti_header(float qfac, short qform_code, short sform_code);

/// Asserts that what() is one line naming the file and containing every part.
void expect_refusal_names(const std::string& what, const fs::path& file, const std::vector<std::string>& parts);

}  // namespace palpa::anatomy_io::test
