// Label volumes to cases: lesions where the labels put them, the same case from a flipped,
// permuted or rotated voxel grid, a fresh press on the imported body as on the body
// authored directly, and every bad volume refused in one line.
#include <gtest/gtest.h>

#include "analytic_bodies.hpp"
#include "palpa/anatomy/import.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::anatomy {
namespace {

using testing::AnalyticBody;

ImportResult import_dome(double voxel, const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  return import_label_volume(testing::voxelize(testing::dome_on_plane(), voxel, rotation), builtin_label_table("generic"),
                             {}, "dome.nii");
}

class LesionAtVoxelSize : public ::testing::TestWithParam<double> {};

TEST_P(LesionAtVoxelSize, ComesOutWithinOneVoxelOfTheLabelledBall) {
  const double voxel = GetParam();
  const ImportResult r = import_dome(voxel);
  ASSERT_EQ(r.lesions.size(), 1u);
  ASSERT_EQ(r.tumours.size(), 1u);
  const auto ball = *testing::dome_on_plane().lesion;
  EXPECT_LE((to_vec3(r.tumours[0].center) - ball.centre).norm(), voxel);
  EXPECT_NEAR(r.tumours[0].radius, ball.radius, voxel);
  EXPECT_EQ(r.tumours[0].modulus, builtin_label_table("generic").find(4)->modulus);
  EXPECT_EQ(r.tumours[0].body, "body");
}

INSTANTIATE_TEST_SUITE_P(Dome, LesionAtVoxelSize, ::testing::Values(0.5e-3, 1e-3, 2e-3));

TEST(ImportVolume, WritesAValidCaseWhoseTumourSitsInsideItsBody) {
  const ImportResult r = import_dome(1e-3);
  const io::CaseFile file = make_case(r, {"dome.nii", std::string(64, '0'), "", "", "generic", "--labels generic"}, "Dome", ExamRegion::FreeSurface);
  ASSERT_EQ(file.bodies.size(), 1u);
  EXPECT_EQ(file.bodies[0].support, mat::Support::Bottom);
  EXPECT_EQ(file.bodies[0].modulus.size(), file.bodies[0].point_count());
  for (double e : file.bodies[0].modulus) EXPECT_NEAR(e, builtin_label_table("generic").find(1)->modulus, 1e-6);
  EXPECT_NO_THROW((void)scene::Scene::build(file, "dome.json"));
  ASSERT_TRUE(file.document.contains("provenance"));
  EXPECT_EQ(file.document["provenance"]["source"], "dome.nii");
  EXPECT_TRUE(file.document.contains("exam_region"));
}

// The voxel grid flipped along i (its direction's first column negated, the origin moved to
// the far end) and with i and k swapped: every voxel centre stays where it was in the world.
LabelVolume flipped_and_permuted(const LabelVolume& v) {
  LabelVolume out = v;
  out.dims = {v.dims[2], v.dims[1], v.dims[0]};
  out.spacing = {v.spacing[2], v.spacing[1], v.spacing[0]};
  out.origin = v.world(v.dims[0] - 1, 0, 0);
  for (std::size_t r = 0; r < 3; ++r) {
    out.direction[3 * r + 0] = v.direction[3 * r + 2];
    out.direction[3 * r + 1] = v.direction[3 * r + 1];
    out.direction[3 * r + 2] = -v.direction[3 * r + 0];
  }
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) out.labels[out.index(k, j, v.dims[0] - 1 - i)] = v.labels[v.index(i, j, k)];
    }
  }
  return out;
}

TEST(ImportVolume, AFlippedAndPermutedVoxelGridGivesTheSameCase) {
  const LabelVolume plain = testing::voxelize(testing::dome_on_plane(), 2e-3);
  const LabelVolume turned = flipped_and_permuted(plain);
  ASSERT_LT((to_vec3(turned.world(7, 3, plain.dims[0] - 1 - 5)) - to_vec3(plain.world(5, 3, 7))).norm(), 1e-12);
  const auto table = builtin_label_table("generic");
  const ImportResult a = import_label_volume(plain, table, {}, "a.nii");
  const ImportResult b = import_label_volume(turned, table, {}, "b.nii");
  ASSERT_EQ(a.body.grid.rows, b.body.grid.rows);
  ASSERT_EQ(a.body.grid.cols, b.body.grid.cols);
  double worst = 0.0;
  for (std::size_t k = 0; k < a.body.grid.point_count(); ++k) {
    worst = std::max(worst, (to_vec3(a.body.grid.medial[k]) - to_vec3(b.body.grid.medial[k])).norm());
    worst = std::max(worst, std::abs(a.body.grid.radius[k] - b.body.grid.radius[k]));
  }
  EXPECT_LT(worst, 1e-6);
  ASSERT_EQ(a.tumours.size(), b.tumours.size());
  EXPECT_LT((to_vec3(a.tumours[0].center) - to_vec3(b.tumours[0].center)).norm(), 1e-9);
}

TEST(ImportVolume, ARotatedVoxelGridGivesTheSameBodyWithinAVoxel) {
  const double voxel = 1e-3;
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.5, Vec3::UnitZ()) * Eigen::AngleAxisd(0.3, Vec3::UnitX())).toRotationMatrix();
  const ImportResult a = import_dome(voxel);
  const ImportResult b = import_dome(voxel, turn);
  const auto ball = *testing::dome_on_plane().lesion;
  ASSERT_EQ(b.tumours.size(), 1u);
  EXPECT_LE((to_vec3(b.tumours[0].center) - ball.centre).norm(), voxel);
  EXPECT_NEAR(b.tumours[0].radius, ball.radius, voxel);
  // The support's plane and the apex come out where they were.
  EXPECT_LT(std::abs(b.surfaces.frame.n.dot(Vec3::UnitZ())), 1.0 + 1e-12);
  EXPECT_GT(b.surfaces.frame.n.z(), 0.999);
  double apex_a = 0.0, apex_b = 0.0;
  for (std::size_t k = 0; k < a.body.grid.point_count(); ++k) apex_a = std::max(apex_a, a.body.grid.medial[k][2] + a.body.grid.radius[k]);
  for (std::size_t k = 0; k < b.body.grid.point_count(); ++k) apex_b = std::max(apex_b, b.body.grid.medial[k][2] + b.body.grid.radius[k]);
  EXPECT_NEAR(apex_a, 0.030, 0.5 * voxel + 0.2e-3);
  EXPECT_NEAR(apex_b, 0.030, 0.5 * voxel + 0.2e-3);
}

// --- refusals: one line, naming the file ---

void expect_refused(const LabelVolume& v, const std::string& words) {
  try {
    (void)import_label_volume(v, builtin_label_table("generic"), {}, "bad.nii");
    ADD_FAILURE() << "accepted; expected a refusal mentioning " << words;
  } catch (const ImportError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("bad.nii"), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

LabelVolume relabelled(LabelVolume v, Label from, Label to) {
  for (auto& l : v.labels) {
    if (l == from) l = to;
  }
  return v;
}

TEST(ImportVolumeRefuses, AVolumeWithNoSupport) {
  expect_refused(relabelled(testing::voxelize(testing::dome_on_plane(), 2e-3), 3, 0), "no support");
}

TEST(ImportVolumeRefuses, AVolumeWithNoTissue) {
  expect_refused(relabelled(relabelled(testing::voxelize(testing::dome_on_plane(), 2e-3), 1, 0), 4, 0), "empty tissue");
}

TEST(ImportVolumeRefuses, ALabelTheTableDoesNotList) {
  LabelVolume v = testing::voxelize(testing::dome_on_plane(), 2e-3);
  v.labels[v.index(30, 30, 12)] = 7;
  expect_refused(v, "label 7");
}

TEST(ImportVolumeRefuses, AnOverhangNamingWhereItIs) {
  AnalyticBody mushroom = testing::dome_on_plane();
  mushroom.lesion.reset();
  const auto dome = mushroom.skin;
  // A shelf of tissue 6 mm thick floating 8 mm above the dome's flank at x > 30 mm.
  LabelVolume v = testing::voxelize(mushroom, 1e-3);
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        const Vec3 p = to_vec3(v.world(i, j, k));
        const double base = dome(p.x(), p.y());
        if (p.x() > 0.030 && p.x() < 0.045 && std::abs(p.y()) < 0.01 && p.z() > base + 0.008 && p.z() < base + 0.014) {
          v.labels[v.index(i, j, k)] = 1;
        }
      }
    }
  }
  expect_refused(v, "overhang at (");
}

// --- the force of a fresh press ---

// The dome authored directly on the same grid: skeleton halfway between the analytic
// surfaces, radius half the thickness, as an instructor's script would write it.
io::CaseFile authored_dome(const FittedBody& like, double modulus) {
  const AnalyticBody dome = testing::dome_on_plane();
  io::CaseFile file;
  mat::BodyGrid grid = like.grid;
  for (int i = 0; i < grid.rows; ++i) {
    for (int j = 0; j < grid.cols; ++j) {
      const auto k = static_cast<std::size_t>(i * grid.cols + j);
      const double x = like.s_sites[static_cast<std::size_t>(i)], y = like.t_sites[static_cast<std::size_t>(j)];
      const bool rim = i == 0 || j == 0 || i == grid.rows - 1 || j == grid.cols - 1;
      const double half = rim ? 0.0 : 0.5 * dome.thickness(x, y);
      grid.medial[k] = {x, y, half};
      grid.radius[k] = half;
    }
  }
  grid.modulus.assign(grid.point_count(), modulus);
  file.bodies.push_back(grid);
  return io::parse_case(io::to_json(file).dump(), "authored.json");
}

// Straight down at (x, y): in 0.02 mm steps from 3 mm above the analytic skin until the
// body pushes back (its own skin), then `depth` further.
double press(const scene::Scene& scene, double x, double y, double depth,
             const AnalyticBody& body = testing::dome_on_plane()) {
  auto state = scene.make_state();
  scene::ProbeOptions options;
  options.remember_side = true;
  double z = body.top(x, y) + 0.003;
  while (scene.probe(Vec3(x, y, z), state, options).force.total.norm() == 0.0 && z > -0.01) z -= 0.02e-3;
  Vec3 last = Vec3::Zero();
  for (int s = 1; s <= 20; ++s) last = scene.probe(Vec3(x, y, z - depth * s / 20.0), state, options).force.total;
  return last.norm();
}

TEST(ImportVolume, AFreshPressFeelsWithinFivePercentOfTheBodyAuthoredDirectly) {
  const ImportResult r = import_dome(1e-3);
  const io::CaseFile imported = make_case(r, {"dome.nii", std::string(64, '0'), "", "", "generic", ""}, "Dome", ExamRegion::Whole);
  const io::CaseFile direct = authored_dome(r.body, builtin_label_table("generic").find(1)->modulus);
  const auto a = scene::Scene::build(imported, "imported"), b = scene::Scene::build(direct, "direct");
  double worst = 0.0;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.02, 0.0}, {-0.015, 0.025}, {0.0, -0.035}, {0.03, 0.03}}) {
    for (double depth : {0.003, 0.008}) {
      if (testing::dome_on_plane().lesion && std::hypot(x - 0.012, y + 0.008) < 0.02) continue;  // over the tumour
      const double fa = press(a, x, y, depth), fb = press(b, x, y, depth);
      EXPECT_GT(fb, 0.0);
      worst = std::max(worst, std::abs(fa / fb - 1.0));
      EXPECT_NEAR(fa / fb, 1.0, 0.05) << "at (" << x * 1e3 << ", " << y * 1e3 << ") mm, " << depth * 1e3 << " mm deep: "
                                      << fa << " N imported, " << fb << " N authored";
    }
  }
  std::printf("fresh presses, imported against authored: largest difference %.1f %%\n", 100.0 * worst);
}

// Ribs under the tissue: the same press, to the same depth below the flat skin, meets the
// support sooner over a rib (23 mm of tissue) than between two (29 mm), and is felt.
TEST(ImportVolume, ADeepPressOverARibFeelsIt) {
  const AnalyticBody ribs = testing::slab_on_ribs();
  const ImportResult r = import_label_volume(testing::voxelize(ribs, 1e-3), builtin_label_table("generic"), {}, "ribs.nii");
  const io::CaseFile file = make_case(r, {"ribs.nii", std::string(64, '0'), "", "", "generic", ""}, "Ribs", ExamRegion::Whole);
  const auto scene = scene::Scene::build(file, "ribs");
  const double crest = 0.035 / 4.0, trough = -0.035 / 4.0;  // where the support is +3 and -3 mm
  for (double y : {-0.01, 0.0, 0.012}) {
    const double over = press(scene, crest, y, 0.018, ribs), between = press(scene, trough, y, 0.018, ribs);
    std::printf("18 mm deep at y = %.0f mm: %.2f N over a rib, %.2f N between ribs\n", y * 1e3, over, between);
    EXPECT_GT(over, 1.3 * between);
  }
}

}  // namespace
}  // namespace palpa::anatomy
