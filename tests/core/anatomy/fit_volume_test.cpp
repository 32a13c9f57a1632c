// The MAT fit of label volumes against bodies known in closed form: the fitted contours lie
// within half a voxel + 0.2 mm of the analytic surfaces away from the rim, at 0.5, 1 and 2 mm.
#include <gtest/gtest.h>

#include <cstdio>

#include "analytic_bodies.hpp"
#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/mat_fit.hpp"
#include "palpa/anatomy/surfaces.hpp"

namespace palpa::anatomy {
namespace {

using testing::AnalyticBody;
using testing::Measured;
using testing::measure;

struct Case {
  const char* name;
  AnalyticBody (*make)();
  double voxel;
};

class FitVolume : public ::testing::TestWithParam<Case> {};

TEST_P(FitVolume, ContoursLieWithinHalfAVoxelPlusPointTwoMillimetresAwayFromTheRim) {
  const Case c = GetParam();
  const AnalyticBody body = c.make();
  const LabelVolume volume = testing::voxelize(body, c.voxel);
  const SurfacePair pair = surfaces_from_volume(volume, builtin_label_table("generic"), "analytic.nii");
  const FittedBody fitted = fit_body_auto(pair, "body");
  const Measured m = measure(body, fitted);
  const double tolerance = 0.5 * c.voxel + 0.2e-3;  // the voxels' own half plus the fit's kFitTarget
  std::printf("%s at %.1f mm: grid %dx%d, %d iterations, support %s; away from the rim: top %.3f mm, bottom %.3f mm "
              "(tolerance %.2f mm; the fit reports %.3f / %.3f)\n",
              c.name, c.voxel * 1e3, fitted.grid.rows, fitted.grid.cols, fitted.report.iterations, pair.support_kind,
              m.top * 1e3, m.bottom * 1e3, tolerance * 1e3, fitted.report.top.interior_max * 1e3,
              fitted.report.bottom.interior_max * 1e3);
  EXPECT_GT(m.points, 1000);
  EXPECT_LE(m.top, tolerance);
  EXPECT_LE(m.bottom, tolerance);
}

INSTANTIATE_TEST_SUITE_P(Analytic, FitVolume,
                         ::testing::Values(Case{"dome", testing::dome_on_plane, 1e-3},
                                           Case{"curved", testing::cap_on_curved_wall, 1e-3},
                                           Case{"ribs", testing::slab_on_ribs, 1e-3},
                                           Case{"dome", testing::dome_on_plane, 2e-3},
                                           Case{"curved", testing::cap_on_curved_wall, 2e-3},
                                           Case{"ribs", testing::slab_on_ribs, 2e-3},
                                           Case{"dome", testing::dome_on_plane, 0.5e-3},
                                           Case{"curved", testing::cap_on_curved_wall, 0.5e-3},
                                           Case{"ribs", testing::slab_on_ribs, 0.5e-3}),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return std::string(param.param.name) + "_" +
                                  std::to_string(static_cast<int>(param.param.voxel * 1e4 + 0.5)) + "tenths_mm";
                         });

}  // namespace
}  // namespace palpa::anatomy
