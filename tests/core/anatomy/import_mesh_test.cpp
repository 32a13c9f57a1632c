// Surface meshes to cases: a skin mesh on a support mesh and a closed mesh on a support
// plane against the analytic bodies, a case's own contours round-tripped through meshes, and
// every bad mesh refused in one line.
#include <gtest/gtest.h>

#include "analytic_meshes.hpp"
#include "palpa/anatomy/import.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"

namespace palpa::anatomy {
namespace {

using testing::AnalyticBody;

// m: as for a volume of 1 mm voxels, half the input's resolution (the triangles' 1 mm
// edges) plus 0.2 mm.
constexpr double kMeshTolerance = 0.5e-3 + kFitTarget;

struct Body {
  const char* name;
  AnalyticBody (*make)();
};

class SkinOnSupport : public ::testing::TestWithParam<Body> {};

TEST_P(SkinOnSupport, ContoursLieOnTheAnalyticSurfacesAwayFromTheRim) {
  const AnalyticBody body = GetParam().make();
  const ImportResult r = import_surfaces(testing::skin_mesh(body), testing::support_mesh(body), 3240.0, {}, "skin.stl",
                                         "support.stl");
  const testing::Measured m = testing::measure(body, r.body);
  std::printf("%s: grid %dx%d, support %s: top %.3f mm (worst at %s), bottom %.3f mm away from the rim; the fit "
              "reports %.3f / %.3f\n",
              GetParam().name, r.body.grid.rows, r.body.grid.cols, r.surfaces.support_kind, m.top * 1e3,
              millimetres(m.worst_top).c_str(), m.bottom * 1e3, r.body.report.top.interior_max * 1e3,
              r.body.report.bottom.interior_max * 1e3);
  EXPECT_GT(m.points, 1000);
  EXPECT_LE(m.top, kMeshTolerance);
  EXPECT_LE(m.bottom, kMeshTolerance);
  EXPECT_EQ(r.body.grid.modulus.size(), r.body.grid.point_count());
}

INSTANTIATE_TEST_SUITE_P(Analytic, SkinOnSupport,
                         ::testing::Values(Body{"dome", testing::dome_on_plane}, Body{"curved", testing::cap_on_curved_wall},
                                           Body{"ribs", testing::slab_on_ribs}),
                         [](const ::testing::TestParamInfo<Body>& param) { return std::string(param.param.name); });

TEST(ClosedMesh, OnItsSupportPlaneGivesTheDome) {
  const AnalyticBody body = testing::dome_on_plane();
  // The plane 2 z - 0 = 0 written with a normal that is not unit, pointing away from the body.
  const ImportResult r = import_closed_mesh(testing::closed_mesh(body), Vec3(0, 0, -2), 0.0, 3240.0, {}, "dome.obj");
  const testing::Measured m = testing::measure(body, r.body);
  EXPECT_GT(r.surfaces.frame.n.z(), 0.999);
  EXPECT_LE(m.top, kMeshTolerance);
  EXPECT_LE(m.bottom, kMeshTolerance);
}

TEST(RoundTrip, ACasesContoursAsMeshesComeBackAsTheSameBody) {
  const AnalyticBody body = testing::dome_on_plane();
  const ImportResult first = import_surfaces(testing::skin_mesh(body), testing::support_mesh(body), 3240.0, {}, "a.stl", "b.stl");
  // The first body's contours, tessellated 4 times per grid interval.
  const mat::MatBody mat = testing::geometry(first.body);
  const auto contour_mesh = [&](const spline::BSplineSurface& surface) {
    TriangleMesh mesh;
    const int n = 4 * (first.body.grid.rows - 1) + 1, m = 4 * (first.body.grid.cols - 1) + 1;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j) {
        double p[3];
        surface.evaluate(static_cast<double>(i) / (n - 1), static_cast<double>(j) / (m - 1), p);
        mesh.points.push_back({p[0], p[1], p[2]});
      }
    }
    for (int i = 0; i + 1 < n; ++i) {
      for (int j = 0; j + 1 < m; ++j) {
        const auto id = [m](int a, int b) { return static_cast<std::int32_t>(a * m + b); };
        mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
    return mesh;
  };
  const ImportResult second =
      import_surfaces(contour_mesh(mat.top()), contour_mesh(mat.bottom()), 3240.0, {}, "top.stl", "bottom.stl");
  // The second fit lands on the first body's contours, and so on the dome.
  EXPECT_LE(second.body.report.top.interior_max, kMeshTolerance);
  EXPECT_LE(second.body.report.bottom.interior_max, kMeshTolerance);
  const testing::Measured m = testing::measure(body, second.body);
  EXPECT_LE(m.top, 2.0 * kMeshTolerance);
  EXPECT_LE(m.bottom, 2.0 * kMeshTolerance);
}

// --- refusals ---

void expect_refused(const std::function<void()>& import, const std::string& file, const std::string& words) {
  try {
    import();
    ADD_FAILURE() << "accepted; expected a refusal mentioning " << words;
  } catch (const ImportError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(MeshRefusals, AnOpenMeshOnASupportPlane) {
  const TriangleMesh skin = testing::skin_mesh(testing::dome_on_plane());
  expect_refused([&] { (void)import_closed_mesh(skin, Vec3(0, 0, 1), 0.0, 3240.0, {}, "open.stl"); }, "open.stl", "open mesh");
}

TEST(MeshRefusals, ANonManifoldEdge) {
  TriangleMesh skin = testing::skin_mesh(testing::dome_on_plane());
  const auto t = skin.triangles[skin.triangles.size() / 2];
  skin.points.push_back({0.0, 0.0, 0.1});
  skin.triangles.push_back({t[0], t[1], static_cast<std::int32_t>(skin.points.size() - 1)});  // a fin on an inner edge
  expect_refused([&] { (void)import_surfaces(skin, testing::support_mesh(testing::dome_on_plane()), 3240.0, {}, "fin.stl", "s.stl"); },
                 "fin.stl", "non-manifold");
}

TEST(MeshRefusals, AnOverhangNamingWhereItIs) {
  const AnalyticBody dome = testing::dome_on_plane();
  TriangleMesh skin = testing::skin_mesh(dome);
  // A shelf 10 mm above the dome's flank: the skin crosses those columns twice.
  const TriangleMesh shelf = testing::height_mesh([&](double x, double y) { return dome.top(x, y) + 0.01; }, dome.half_x, 2e-3,
                                                  [](double x, double y) { return x > 0.03 && x < 0.045 && std::abs(y) < 0.01; });
  const auto base = static_cast<std::int32_t>(skin.points.size());
  skin.points.insert(skin.points.end(), shelf.points.begin(), shelf.points.end());
  for (const auto& t : shelf.triangles) skin.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  expect_refused([&] { (void)import_surfaces(skin, testing::support_mesh(dome), 3240.0, {}, "shelf.stl", "s.stl"); }, "shelf.stl",
                 "overhang at (");
}

TEST(MeshRefusals, AClosedMeshAwayFromItsSupportPlane) {
  const TriangleMesh mesh = testing::closed_mesh(testing::dome_on_plane());
  expect_refused([&] { (void)import_closed_mesh(mesh, Vec3(0, 0, 1), 0.005, 3240.0, {}, "lifted.ply"); }, "lifted.ply",
                 "the support plane");
}

TEST(MeshRefusals, AnEmptyMesh) {
  expect_refused([&] { (void)import_surfaces({}, testing::support_mesh(testing::dome_on_plane()), 3240.0, {}, "empty.stl", "s.stl"); },
                 "empty.stl", "no triangles");
}

}  // namespace
}  // namespace palpa::anatomy
