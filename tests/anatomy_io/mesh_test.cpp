// Meshes: STL (binary and ASCII), OBJ and PLY round trips of an icosphere, coincident points
// merged, and headers that lie about their size refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "palpa/anatomy_io/anatomy_io.hpp"
#include "support.hpp"

namespace palpa::anatomy_io::test {
namespace {

std::string refusal(const fs::path& file) {
  try {
    read_mesh(file);
    ADD_FAILURE() << file << " was read";
  } catch (const anatomy::ImportError& e) {
    return e.what();
  }
  return {};
}

struct Case {
  std::string ext;
  bool ascii;
};

class MeshRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(MeshRoundTrip, GivesTheSamePointsAndTriangles) {
  ScratchDir dir;
  const anatomy::TriangleMesh m = icosphere();
  ASSERT_EQ(m.points.size(), 42u);
  ASSERT_EQ(m.triangles.size(), 80u);
  const fs::path file = dir / ("sphere" + GetParam().ext);
  write_mesh(file, m, 1e-3, GetParam().ascii);
  const anatomy::TriangleMesh r = read_mesh(file, 1e-3);
  // STL stores every triangle's corners: 240 points merged back into 42.
  ASSERT_EQ(r.points.size(), 42u);
  ASSERT_EQ(r.triangles.size(), 80u);
  // float32 (binary STL, PLY) or 6 significant digits (ASCII) of 50 mm: within 0.1 um.
  for (const auto& p : m.points) {
    double best = 1e9;
    for (const auto& q : r.points) {
      best = std::min(best, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
    }
    EXPECT_LT(best, 1e-7);
  }
  for (const auto& t : r.triangles) {
    for (std::int32_t i : t) EXPECT_TRUE(i >= 0 && i < 42);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip,
                         ::testing::Values(Case{".stl", false}, Case{".stl", true}, Case{".obj", false}, Case{".ply", false}),
                         [](const auto& param_info) { return param_info.param.ext.substr(1) + (param_info.param.ascii ? "_ascii" : ""); });

TEST(MeshUnits, CoordinatesAreScaledByMetresPerUnit) {
  ScratchDir dir;
  write_mesh(dir / "m.ply", icosphere(), 1.0);  // written in metres
  const anatomy::TriangleMesh r = read_mesh(dir / "m.ply", 1e-3);  // read as if millimetres
  double radius = std::hypot(r.points[0][0], r.points[0][1], r.points[0][2]);
  EXPECT_NEAR(radius, 0.05e-3, 1e-10);
}

// Some exporters start a binary STL's 80-byte header with "solid" too: its size, 84 + 50 n,
// tells it from ASCII.
TEST(MeshRoundTrip, BinaryStlWhoseHeaderSaysSolid) {
  ScratchDir dir;
  write_mesh(dir / "solid.stl", icosphere());
  std::string bytes = read_bytes(dir / "solid.stl");
  const std::string header = "solid exported by a tool that writes binary";
  std::copy(header.begin(), header.end(), bytes.begin());
  write_bytes(dir / "solid.stl", bytes);
  const anatomy::TriangleMesh r = read_mesh(dir / "solid.stl");
  EXPECT_EQ(r.points.size(), 42u);
  EXPECT_EQ(r.triangles.size(), 80u);
}

TEST(MeshRefusals, BinaryStlWithAWrongCountIsRefused) {
  ScratchDir dir;
  write_mesh(dir / "count.stl", icosphere());
  std::string bytes = read_bytes(dir / "count.stl");
  const std::uint32_t wrong = 81;
  std::memcpy(bytes.data() + 80, &wrong, 4);
  write_bytes(dir / "count.stl", bytes);
  expect_refusal_names(refusal(dir / "count.stl"), dir / "count.stl", {"triangle count", "81"});
  const std::uint32_t huge = 0xffffffffu;
  std::memcpy(bytes.data() + 80, &huge, 4);
  write_bytes(dir / "huge.stl", bytes);
  expect_refusal_names(refusal(dir / "huge.stl"), dir / "huge.stl", {"triangle count", "more than"});
  write_bytes(dir / "empty.stl", std::string(84, '\0'));
  expect_refusal_names(refusal(dir / "empty.stl"), dir / "empty.stl", {"no triangles"});
}

TEST(MeshRefusals, PlyCountsIndicesAndCoordinatesAreChecked) {
  ScratchDir dir;
  write_bytes(dir / "huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n");
  expect_refusal_names(refusal(dir / "huge.ply"), dir / "huge.ply", {"element vertex"});
  write_bytes(dir / "index.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_refusal_names(refusal(dir / "index.ply"), dir / "index.ply", {"polygon 0", "out of range"});
  write_bytes(dir / "nan.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
  expect_refusal_names(refusal(dir / "nan.ply"), dir / "nan.ply", {"point 1", "not finite"});
  write_bytes(dir / "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expect_refusal_names(refusal(dir / "index.obj"), dir / "index.obj", {});
  write_bytes(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const anatomy::TriangleMesh quad = read_mesh(dir / "quad.obj");
  EXPECT_EQ(quad.triangles.size(), 2u);  // polygons triangulated
  write_bytes(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  expect_refusal_names(refusal(dir / "lines.obj"), dir / "lines.obj", {"triangles", "none"});
  write_bytes(dir / "garbage.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 zero\n");
  expect_refusal_names(refusal(dir / "garbage.stl"), dir / "garbage.stl", {});
  expect_refusal_names(refusal(dir / "mesh.off"), dir / "mesh.off", {"extension"});
  expect_refusal_names(refusal(dir / "absent.stl"), dir / "absent.stl", {"does not exist"});
}

}  // namespace
}  // namespace palpa::anatomy_io::test
