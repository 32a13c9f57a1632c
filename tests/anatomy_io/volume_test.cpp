// Label volumes: round trips of every format with an oblique placement, hand-written NIfTI,
// MetaImage and NRRD headers against values computed by hand, and malformed files refused
// with one line naming the file and the field.
#include <gtest/gtest.h>

#include <chrono>
#include <algorithm>
#include <cstring>

#include "palpa/anatomy_io/anatomy_io.hpp"
#include "support.hpp"

namespace palpa::anatomy_io::test {
namespace {

void expect_near3(const std::array<double, 3>& a, const std::array<double, 3>& b, double tolerance) {
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(a[r], b[r], tolerance) << "coordinate " << r;
}

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, KeepsLabelsAndWorldPlacement) {
  ScratchDir dir;
  const anatomy::LabelVolume a = oblique_ball();
  const fs::path file = dir / ("ball" + GetParam());
  write_label_volume(file, a);
  const anatomy::LabelVolume r = read_label_volume(file);
  ASSERT_EQ(r.dims, a.dims);
  EXPECT_EQ(r.labels, a.labels);
  expect_near3(world_of_label(r, 7), a.world(3, 5, 7), 1e-9);
  expect_near3(r.world(19, 23, 27), a.world(19, 23, 27), 1e-9);
  expect_near3(r.world(0, 0, 0), a.world(0, 0, 0), 1e-9);
}

// Patient models label with negative integers and extreme values; every format keeps them.
TEST_P(RoundTrip, KeepsNegativeAndLargeLabels) {
  ScratchDir dir;
  anatomy::LabelVolume a = oblique_ball();
  a.labels[0] = -4;
  a.labels[1] = -2147483647 - 1;
  a.labels[2] = 2147483647;
  a.labels[3] = 70000;
  const fs::path file = dir / ("signed" + GetParam());
  write_label_volume(file, a);
  EXPECT_EQ(read_label_volume(file).labels, a.labels);
}

TEST_P(RoundTrip, PermutedAndFlippedAxesLandOnTheSameWorldPositions) {
  ScratchDir dir;
  const anatomy::LabelVolume a = oblique_ball();
  anatomy::LabelVolume b = permuted_flipped(a);
  expect_near3(world_of_label(b, 7), a.world(3, 5, 7), 1e-12);  // the compensation itself
  // NIfTI-1 stores float32: B's origin (A's far corner) rounded to float millimetres moves
  // it by a few nanometres; the other formats carry it as written.
  const bool nifti = GetParam().find("ni") != std::string::npos || GetParam().find("NI") != std::string::npos;
  if (nifti) {
    for (double& o : b.origin) o = static_cast<double>(static_cast<float>(o * 1e3)) * 1e-3;
  }
  const fs::path file = dir / ("flipped" + GetParam());
  write_label_volume(file, b);
  const anatomy::LabelVolume r = read_label_volume(file);
  ASSERT_EQ(r.dims, (std::array<int, 3>{28, 20, 24}));
  EXPECT_EQ(r.labels, b.labels);
  expect_near3(world_of_label(r, 7), world_of_label(b, 7), 1e-9);
  expect_near3(world_of_label(r, 7), a.world(3, 5, 7), nifti ? 1e-8 : 1e-9);
  expect_near3(centroid_of_label(r, 3), centroid_of_label(a, 3), nifti ? 1e-8 : 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values(".nii", ".nii.gz", ".nrrd", ".nhdr", ".mha", ".mhd", ".vti", ".NII.GZ"),
                         [](const auto& param_info) {
                           std::string name = param_info.param.substr(1);
                           for (char& c : name) c = c == '.' ? '_' : c;
                           return name;
                         });

// Method 2: x = R [2 i, 3 j, qfac 4 k] + qoffset with R a quarter turn about z, so
// (i, j, k) = (1, 2, 3) gives R (2, 6, 12 qfac) + (10, 20, 30) = (-6 + 10, 2 + 20, 12 qfac + 30).
TEST(NiftiHeader, QformWithQfacMinusOneReversesTheThirdAxis) {
  ScratchDir dir;
  write_bytes(dir / "q.nii", nifti_header(-1.0f, 1, 0));
  write_bytes(dir / "p.nii", nifti_header(1.0f, 1, 0));
  const anatomy::LabelVolume q = read_label_volume(dir / "q.nii");
  const anatomy::LabelVolume p = read_label_volume(dir / "p.nii");
  // The quaternion is float32 in the header: a and d agree with 1/sqrt(2) to 1e-7.
  expect_near3(world_of_label(q, 5), {0.004, 0.022, 0.018}, 1e-8);
  expect_near3(world_of_label(p, 5), {0.004, 0.022, 0.042}, 1e-8);
  EXPECT_NEAR(q.spacing[2], 0.004, 1e-12);
  EXPECT_NEAR(q.direction[8], -1.0, 1e-7);
  EXPECT_NEAR(q.direction[3], 1.0, 1e-7);  // axis i along +y
}

// The writer's qform (quaternion, qfac = -1 for a mirrored placement) says what its sform
// says: with sform_code set to 0 the reader falls back to it. The quaternion is float32:
// within 10 nm over the volume.
TEST(NiftiHeader, WrittenQformAgreesWithTheSform) {
  ScratchDir dir;
  const anatomy::LabelVolume a = oblique_ball();
  const anatomy::LabelVolume flipped = permuted_flipped(a);
  for (const anatomy::LabelVolume* p : {&a, &flipped}) {
    const anatomy::LabelVolume& v = *p;
    write_label_volume(dir / "q.nii", v);
    std::string bytes = read_bytes(dir / "q.nii");
    float qfac = 0;
    std::memcpy(&qfac, bytes.data() + 76, 4);
    const std::int16_t no_sform = 0;
    std::memcpy(bytes.data() + 254, &no_sform, 2);
    write_bytes(dir / "q.nii", bytes);
    const anatomy::LabelVolume r = read_label_volume(dir / "q.nii");
    EXPECT_EQ(qfac, p == &a ? 1.0f : -1.0f);
    expect_near3(world_of_label(r, 7), a.world(3, 5, 7), 1e-8);
    expect_near3(r.world(v.dims[0] - 1, v.dims[1] - 1, v.dims[2] - 1), v.world(v.dims[0] - 1, v.dims[1] - 1, v.dims[2] - 1), 1e-8);
  }
}

// Method 3 wins over the qform: x = srow (i, j, k, 1): (1, 2, 3) gives
// (-2.5 * 3 + 7, 1.5 * 1 + 8, 3.5 * 2 + 9) = (-0.5, 9.5, 16) mm.
TEST(NiftiHeader, SformIsUsedWhenItsCodeIsPositive) {
  ScratchDir dir;
  write_bytes(dir / "s.nii", nifti_header(-1.0f, 1, 2));
  const anatomy::LabelVolume s = read_label_volume(dir / "s.nii");
  expect_near3(world_of_label(s, 5), {-0.0005, 0.0095, 0.016}, 1e-12);
  EXPECT_NEAR(s.spacing[0], 0.0015, 1e-15);
  EXPECT_NEAR(s.spacing[1], 0.0035, 1e-15);
  EXPECT_NEAR(s.spacing[2], 0.0025, 1e-15);
}

TEST(NiftiHeader, GzipAndByteSwappedHeadersReadTheSame) {
  ScratchDir dir;
  std::string bytes = nifti_header(-1.0f, 1, 2);
  // Big-endian copy: swap every field the reader uses.
  std::string big = bytes;
  auto swap_at = [&big](std::size_t at, std::size_t size) { std::reverse(big.begin() + static_cast<long>(at), big.begin() + static_cast<long>(at + size)); };
  swap_at(0, 4);
  for (std::size_t n = 0; n < 8; ++n) swap_at(40 + 2 * n, 2);
  swap_at(70, 2);
  swap_at(72, 2);
  for (std::size_t n = 0; n < 8; ++n) swap_at(76 + 4 * n, 4);
  for (std::size_t at : {std::size_t{108}, std::size_t{112}, std::size_t{116}}) swap_at(at, 4);
  swap_at(252, 2);
  swap_at(254, 2);
  for (std::size_t n = 0; n < 21; ++n) swap_at(256 + 4 * n, 4);
  write_bytes(dir / "big.nii", big);
  const anatomy::LabelVolume s = read_label_volume(dir / "big.nii");
  expect_near3(world_of_label(s, 5), {-0.0005, 0.0095, 0.016}, 1e-12);
}

// ITK's LPS: TransformMatrix lists axis i's direction (0, 1, 0), then axis j's (-1, 0, 0),
// then axis k's (0, 0, 1); voxel (1, 2, 3) at Offset + 1 (0, 1, 0) + 2 * 2 (-1, 0, 0) +
// 3 * 3 (0, 0, 1) = (6, 21, 39) LPS = (-6, -21, 39) RAS, mm.
TEST(LpsFiles, MetaImageIsReadAsRas) {
  ScratchDir dir;
  std::string data(2 * 3 * 4, '\0');
  data[1 + 2 * (2 + 3 * 3)] = 9;
  write_bytes(dir / "lps.mha", "ObjectType = Image\nNDims = 3\nBinaryData = True\nCompressedData = False\n"
                               "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = 10 20 30\nElementSpacing = 1 2 3\n"
                               "DimSize = 2 3 4\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + data);
  const anatomy::LabelVolume v = read_label_volume(dir / "lps.mha");
  expect_near3(world_of_label(v, 9), {-0.006, -0.021, 0.039}, 1e-12);
  expect_near3(v.origin, {-0.010, -0.020, 0.030}, 1e-12);
}

TEST(LpsFiles, NrrdIsReadAsRas) {
  ScratchDir dir;
  std::string data(2 * 3 * 4, '\0');
  data[1 + 2 * (2 + 3 * 3)] = 9;
  write_bytes(dir / "lps.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 3 4\n"
                                "space directions: (0,1,0) (-2,0,0) (0,0,3)\nendian: little\nencoding: raw\n"
                                "space origin: (10,20,30)\n\n" + data);
  const anatomy::LabelVolume v = read_label_volume(dir / "lps.nrrd");
  expect_near3(world_of_label(v, 9), {-0.006, -0.021, 0.039}, 1e-12);
}

TEST(LpsFiles, NrrdWithoutSpaceUsesSpacingsOnTheAxes) {
  ScratchDir dir;
  std::string data(2 * 3 * 4 * 2, '\0');
  data[2 * (1 + 2 * (2 + 3 * 3))] = 1;  // big-endian 256
  write_bytes(dir / "plain.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 3 4\nspacings: 1 2 3\n"
                                  "endian: big\nencoding: raw\n\n" + data);
  const anatomy::LabelVolume v = read_label_volume(dir / "plain.nrrd");
  expect_near3(world_of_label(v, 256), {0.001, 0.004, 0.009}, 1e-12);
}

}  // namespace
}  // namespace palpa::anatomy_io::test
