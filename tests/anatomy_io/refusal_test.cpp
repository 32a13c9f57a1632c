// Malformed label volumes: each refused with one line naming the file and the field, the
// huge headers before any allocation (in milliseconds).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstring>

#include <sys/stat.h>

#include "palpa/anatomy_io/anatomy_io.hpp"
#include "support.hpp"

namespace palpa::anatomy_io::test {
namespace {

std::string refusal(const fs::path& file) {
  try {
    const anatomy::LabelVolume v = read_label_volume(file);
    ADD_FAILURE() << file << " was read: " << v.dims[0] << " x " << v.dims[1] << " x " << v.dims[2];
  } catch (const anatomy::ImportError& e) {
    return e.what();
  }
  return {};
}

std::string nrrd(const std::string& fields, const std::string& data) {
  return "NRRD0004\ndimension: 3\nendian: little\nencoding: raw\n" + fields + "\n" + data;
}

std::string mha(const std::string& fields, const std::string& data) {
  return "ObjectType = Image\nNDims = 3\nBinaryData = True\n" + fields + "ElementDataFile = LOCAL\n" + data;
}

void expect_fast_refusal(const fs::path& file, const std::string& field) {
  const auto start = std::chrono::steady_clock::now();
  const std::string what = refusal(file);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  expect_refusal_names(what, file, {field});
  std::printf("huge header %s refused in %.3f ms: %s\n", file.filename().c_str(), ms, what.c_str());
  EXPECT_LT(ms, 100.0);  // sized before allocation; reading 2^40 voxels would take hours
}

TEST(HugeHeader, NiftiNrrdAndMetaImageAreRefusedBeforeAllocation) {
  ScratchDir dir;
  const anatomy::LabelVolume small = oblique_ball();
  write_label_volume(dir / "huge.nii", small);
  std::string nii = read_bytes(dir / "huge.nii");
  const std::int16_t big[3] = {32767, 32767, 32767};
  std::memcpy(nii.data() + 42, big, sizeof big);
  write_bytes(dir / "huge.nii", nii);
  expect_fast_refusal(dir / "huge.nii", "dim");
  write_bytes(dir / "huge.nrrd", nrrd("type: uchar\nsizes: 1048576 1048576 1\nspacings: 1 1 1\n", "x"));
  expect_fast_refusal(dir / "huge.nrrd", "sizes");
  write_bytes(dir / "huge.mha", mha("DimSize = 1048576 1048576 1\nElementSpacing = 1 1 1\nElementType = MET_UCHAR\n", "x"));
  expect_fast_refusal(dir / "huge.mha", "DimSize");
  write_bytes(dir / "zero.mha", mha("DimSize = 4 0 4\nElementSpacing = 1 1 1\nElementType = MET_UCHAR\n", "x"));
  expect_refusal_names(refusal(dir / "zero.mha"), dir / "zero.mha", {"DimSize", "at least 1"});
  write_bytes(dir / "negative.nrrd", nrrd("type: uchar\nsizes: 4 -4 4\nspacings: 1 1 1\n", "x"));
  expect_refusal_names(refusal(dir / "negative.nrrd"), dir / "negative.nrrd", {"sizes"});
}

// A file over 2 GiB is refused by its size before a byte is read (a sparse file: no disk).
TEST(HugeFile, OverTwoGibibytesIsRefusedByItsSize) {
  ScratchDir dir;
  for (const std::string name : {"big.nii", "big.stl"}) {
    write_bytes(dir / name, "x");
    fs::resize_file(dir / name, (std::uintmax_t{1} << 31) + 1);
    std::string what;
    try {
      if (name.ends_with(".stl")) {
        read_mesh(dir / name);
      } else {
        read_label_volume(dir / name);
      }
    } catch (const anatomy::ImportError& e) {
      what = e.what();
    }
    expect_refusal_names(what, dir / name, {"file", "2147483649 bytes"});
  }
}

TEST(Truncated, DataShorterThanTheHeaderSaysIsRefused) {
  ScratchDir dir;
  const anatomy::LabelVolume v = oblique_ball();
  for (const std::string ext : {".nii", ".nii.gz", ".nrrd", ".mha", ".vti"}) {
    const fs::path file = dir / ("short" + ext);
    write_label_volume(file, v);
    std::string bytes = read_bytes(file);
    // The end of the data; for VTK XML, halfway into the appended data (its reader
    // forgives missing closing tags).
    const std::size_t appended = bytes.find("<AppendedData");
    bytes.resize(appended == std::string::npos ? bytes.size() - 20 : (appended + bytes.size()) / 2);
    write_bytes(file, bytes);
    const std::string what = refusal(file);
    expect_refusal_names(what, file, {});
    if (ext != ".vti") {
      EXPECT_NE(what.find("truncated"), std::string::npos) << what;
    }
  }
  write_label_volume(dir / "detached.nhdr", v);
  std::string raw = read_bytes(dir / "detached.raw");
  raw.pop_back();
  write_bytes(dir / "detached.raw", raw);
  expect_refusal_names(refusal(dir / "detached.nhdr"), dir / "detached.nhdr", {"data", "truncated"});
}

TEST(BadGeometry, SpacingOriginAndDirectionAreChecked) {
  ScratchDir dir;
  const std::string voxels(8, '\0');
  const std::vector<std::pair<std::string, std::pair<std::string, std::string>>> cases{
      {"zero_spacing.nrrd", {nrrd("type: uchar\nsizes: 2 2 2\nspacings: 0 1 1\n", voxels), "spacings"}},
      {"nan_spacing.nrrd", {nrrd("type: uchar\nsizes: 2 2 2\nspacings: nan 1 1\n", voxels), "spacings"}},
      {"negative_spacing.mha", {mha("DimSize = 2 2 2\nElementSpacing = 1 -1 1\nElementType = MET_UCHAR\n", voxels), "ElementSpacing"}},
      {"sheared.nrrd", {nrrd("type: uchar\nsizes: 2 2 2\nspace: RAS\nspace directions: (1,0,0) (1,1,0) (0,0,1)\n", voxels),
                        "space directions"}},
      {"sheared.mha", {mha("DimSize = 2 2 2\nTransformMatrix = 1 0 0 0.5 1 0 0 0 1\nElementType = MET_UCHAR\n", voxels),
                       "TransformMatrix"}},
      {"long_axis.mha", {mha("DimSize = 2 2 2\nTransformMatrix = 1.5 0 0 0 1 0 0 0 1\nElementType = MET_UCHAR\n", voxels),
                         "TransformMatrix"}},
      {"line_skip.nrrd", {nrrd("type: uchar\nsizes: 2 2 2\nspacings: 1 1 1\nline skip: 2\n", voxels), "line skip"}},
      {"inf_origin.nrrd", {nrrd("type: uchar\nsizes: 2 2 2\nspace: LPS\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
                                "space origin: (inf,0,0)\n", voxels), "space origin"}},
  };
  for (const auto& [name, c] : cases) {
    write_bytes(dir / name, c.first);
    expect_refusal_names(refusal(dir / name), dir / name, {c.second});
  }
  // NIfTI: a sheared sform, and a zero pixdim under the qform.
  anatomy::LabelVolume v = oblique_ball();
  write_label_volume(dir / "sheared.nii", v);
  std::string nii = read_bytes(dir / "sheared.nii");
  const float shear = 0.5f;
  std::memcpy(nii.data() + 280 + 4, &shear, 4);
  write_bytes(dir / "sheared.nii", nii);
  expect_refusal_names(refusal(dir / "sheared.nii"), dir / "sheared.nii", {"srow", "orthonormal"});
  const std::int16_t no_sform = 0;
  const float zero = 0.0f;
  std::memcpy(nii.data() + 254, &no_sform, 2);
  std::memcpy(nii.data() + 80, &zero, 4);
  write_bytes(dir / "zero_pixdim.nii", nii);
  expect_refusal_names(refusal(dir / "zero_pixdim.nii"), dir / "zero_pixdim.nii", {"pixdim", "positive"});
}

TEST(BadLabels, ValuesBeyondA32BitIntegerAndFractionsAreRefusedWithTheirVoxel) {
  ScratchDir dir;
  // Negative labels are labels (patient MRI models label lesions -4 and -3).
  std::string shorts(2 * 2 * 2 * 2, '\0');
  shorts[2 * 5] = static_cast<char>(0xfe);  // voxel 5 = (1, 0, 1): -2
  shorts[2 * 5 + 1] = static_cast<char>(0xff);
  write_bytes(dir / "negative.nrrd", nrrd("type: short\nsizes: 2 2 2\nspacings: 1 1 1\n", shorts));
  EXPECT_EQ(read_label_volume(dir / "negative.nrrd").labels, (std::vector<anatomy::Label>{0, 0, 0, 0, 0, -2, 0, 0}));
  std::string uints(4 * 8, '\0');
  const std::uint32_t large = 3000000000u;  // above 2^31 - 1
  std::memcpy(uints.data() + 4 * 7, &large, 4);
  write_bytes(dir / "large.mha", mha("DimSize = 2 2 2\nElementType = MET_UINT\n", uints));
  expect_refusal_names(refusal(dir / "large.mha"), dir / "large.mha", {"voxel (1, 1, 1)", "3000000000", "32-bit"});
  std::string doubles(8 * 8, '\0');
  const double below = -3e9;
  std::memcpy(doubles.data() + 8 * 2, &below, 8);
  write_bytes(dir / "below.nrrd", nrrd("type: double\nsizes: 2 2 2\nspacings: 1 1 1\n", doubles));
  expect_refusal_names(refusal(dir / "below.nrrd"), dir / "below.nrrd", {"voxel (0, 1, 0)", "32-bit"});
  std::string floats(4 * 8, '\0');
  const float whole = 4.0f, fraction = 2.5f;
  std::memcpy(floats.data(), &whole, 4);
  std::memcpy(floats.data() + 4 * 3, &fraction, 4);
  write_bytes(dir / "fraction.nrrd", nrrd("type: float\nsizes: 2 2 2\nspacings: 1 1 1\n", floats));
  expect_refusal_names(refusal(dir / "fraction.nrrd"), dir / "fraction.nrrd", {"voxel (1, 1, 0)", "2.5", "not a label volume"});
  // Whole-number floats are labels (some tools write labels as floats).
  std::memcpy(floats.data() + 4 * 3, &whole, 4);
  write_bytes(dir / "whole.nrrd", nrrd("type: float\nsizes: 2 2 2\nspacings: 1 1 1\n", floats));
  const anatomy::LabelVolume v = read_label_volume(dir / "whole.nrrd");
  EXPECT_EQ(v.labels, (std::vector<anatomy::Label>{4, 0, 0, 4, 0, 0, 0, 0}));
}

TEST(BadFiles, UnknownExtensionMissingFileAndCorruptGzip) {
  ScratchDir dir;
  write_bytes(dir / "labels.png", "not an image");
  expect_refusal_names(refusal(dir / "labels.png"), dir / "labels.png", {"extension"});
  expect_refusal_names(refusal(dir / "absent.nii"), dir / "absent.nii", {"does not exist"});
  write_label_volume(dir / "corrupt.nii.gz", oblique_ball());
  std::string gz = read_bytes(dir / "corrupt.nii.gz");
  for (std::size_t n = 10; n < 40; ++n) gz[n] = static_cast<char>(0xff);  // past the gzip member header
  write_bytes(dir / "corrupt.nii.gz", gz);
  expect_refusal_names(refusal(dir / "corrupt.nii.gz"), dir / "corrupt.nii.gz", {"corrupt"});
  write_label_volume(dir / "corrupt.mha", oblique_ball());
  std::string z = read_bytes(dir / "corrupt.mha");
  const std::size_t data = z.find("LOCAL\n") + 6;
  for (std::size_t n = data + 2; n < data + 40; ++n) z[n] = static_cast<char>(0xff);
  write_bytes(dir / "corrupt.mha", z);
  expect_refusal_names(refusal(dir / "corrupt.mha"), dir / "corrupt.mha", {"data", "corrupt"});
  // A flipped bit late in the stream: only the checksum at its end can tell.
  write_label_volume(dir / "crc.nrrd", oblique_ball());
  std::string crc = read_bytes(dir / "crc.nrrd");
  crc[crc.size() - 6] = static_cast<char>(crc[crc.size() - 6] ^ 0x10);  // in the CRC-32
  write_bytes(dir / "crc.nrrd", crc);
  expect_refusal_names(refusal(dir / "crc.nrrd"), dir / "crc.nrrd", {"data", "corrupt", "check"});
  write_bytes(dir / "garbage.vti", "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\"><Image WholeExtent=\"0 1");
  ::testing::internal::CaptureStderr();
  const std::string garbage = refusal(dir / "garbage.vti");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");  // VTK's own error output stays quiet
  expect_refusal_names(garbage, dir / "garbage.vti", {"header", "parsing"});
  write_bytes(dir / "notnifti.nii", std::string(400, 'x'));
  expect_refusal_names(refusal(dir / "notnifti.nii"), dir / "notnifti.nii", {"sizeof_hdr"});
}

}  // namespace
}  // namespace palpa::anatomy_io::test

namespace palpa::anatomy_io::test {
namespace {

// A header names its detached data; it may name only a regular file beside it, so that a
// hostile header can make Palpa read neither any file on the machine nor a pipe forever.
TEST(DetachedData, OnlyARegularFileBesideTheHeaderIsRead) {
  ScratchDir dir;
  fs::create_directories(dir / "inner");
  write_bytes(dir / "outside.raw", std::string(8, '\1'));
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nspacings: 1 1 1\nencoding: raw\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"up.nhdr", "../outside.raw"}, {"absolute.nhdr", (dir / "outside.raw").string()}, {"dot.nhdr", ".."}};
  for (const auto& [name, data] : cases) {
    write_bytes(dir / "inner" / name, head + "data file: " + data + "\n");
    const std::string what = refusal(dir / "inner" / name);
    expect_refusal_names(what, dir / "inner" / name, {"data file"});
    EXPECT_NE(what.find("beside the header"), std::string::npos) << what;
  }
  ASSERT_EQ(mkfifo((dir / "inner" / "pipe.raw").c_str(), 0600), 0);
  write_bytes(dir / "inner" / "pipe.nhdr", head + "data file: pipe.raw\n");
  const std::string what = refusal(dir / "inner" / "pipe.nhdr");
  EXPECT_NE(what.find("not a regular file"), std::string::npos) << what;
  write_bytes(dir / "inner" / "beside.raw", std::string(8, '\1'));
  write_bytes(dir / "inner" / "beside.nhdr", head + "data file: beside.raw\n");
  EXPECT_EQ(read_label_volume(dir / "inner" / "beside.nhdr").labels.size(), 8u);
}

}  // namespace
}  // namespace palpa::anatomy_io::test
