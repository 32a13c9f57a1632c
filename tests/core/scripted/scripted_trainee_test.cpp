// The scripted trainee's plan: region, continuity, coverage, pressure; its capabilities.
#include <gtest/gtest.h>

#include "scripted_test_support.hpp"
#include "palpa/scripted/scripted_trainee.hpp"

namespace palpa {
namespace {

using scripted::Style;
using scripted_test::column_at;
using scripted_test::default_case;

const scene::Scene& default_scene() {
  static const auto scene = scene::Scene::build(default_case(), "default.json");
  return scene;
}

// Share of the top contour's area (parameter grid weighted by the area element) within
// `pad` of some spot's top point.
double coverage(const scripted::ScriptedTrainee& trainee, const mat::MatBody& body, double pad) {
  constexpr int n = 120;
  double covered = 0.0, total = 0.0;
  const double h = 1.0 / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) * h, v = (j + 0.5) * h;
      const Vec3 p = column_at(body, u, v).top();
      const Vec3 pu = column_at(body, u + h / 2, v).top() - column_at(body, u - h / 2, v).top();
      const Vec3 pv = column_at(body, u, v + h / 2).top() - column_at(body, u, v - h / 2).top();
      const double area = pu.cross(pv).norm();
      total += area;
      for (const auto& s : trainee.spots()) {
        if ((s.top - p).norm() <= pad) {
          covered += area;
          break;
        }
      }
    }
  }
  return covered / total;
}

TEST(ScriptedTrainee, StylesParseAndNameTheDevice) {
  for (Style s : {Style::Expert, Style::Sloppy, Style::Light}) {
    EXPECT_EQ(scripted::style_from_string(scripted::to_string(s)), s);
  }
  EXPECT_FALSE(scripted::style_from_string("Expert").has_value());
  scripted::ScriptedTrainee trainee(default_scene(), scripted::whole_top_contours(default_scene()), Style::Expert, 1);
  EXPECT_EQ(trainee.capabilities().name, "scripted trainee (expert)");
  EXPECT_EQ(trainee.capabilities().max_force, 30.0);
  EXPECT_TRUE(trainee.capabilities().force_output);
}

TEST(ScriptedTrainee, ExpertCoversTheTopContourSloppyDoesNot) {
  const auto& scene = default_scene();
  const auto region = scripted::whole_top_contours(scene);
  scripted::ScriptedTrainee expert(scene, region, Style::Expert, 1);
  scripted::ScriptedTrainee sloppy(scene, region, Style::Sloppy, 1);
  const double pad = expert.parameters().pad_radius;
  EXPECT_EQ(pad, 7.5e-3);
  EXPECT_GE(coverage(expert, scene.body(0).body, pad), 0.95);
  EXPECT_LT(coverage(sloppy, scene.body(0).body, pad), 0.9);
  // MammaCare pace: the expert's scan of the default breast takes 1.5 to 3 minutes.
  EXPECT_GT(expert.scan_duration(), 90.0);
  EXPECT_LT(expert.scan_duration(), 180.0);
}

// Plays a plan with no force felt (nothing suspicious, so no detours): the probe moves
// continuously, never faster than the pressing speed, and stays over the region.
TEST(ScriptedTrainee, PlanIsContinuousAndStaysOverTheRegion) {
  const auto& scene = default_scene();
  const std::vector<scripted::ExamRect> region{{0, 0.3, 0.5, 0.55, 0.8}};
  for (Style style : {Style::Expert, Style::Light}) {
    scripted::ScriptedTrainee trainee(scene, region, style, 3);
    ASSERT_FALSE(trainee.spots().empty());
    for (const auto& s : trainee.spots()) {
      EXPECT_GE(s.u, 0.3);
      EXPECT_LE(s.u, 0.5);
      EXPECT_GE(s.v, 0.55);
      EXPECT_LE(s.v, 0.8);
    }
    const double dt = 1e-3;
    const double vmax = std::max(trainee.parameters().move_speed, trainee.parameters().press_speed);
    engine::DevicePose pose;
    trainee.read(0.0, pose);
    Vec3 prev = pose.position;
    const auto& body = scene.body(0);
    double worst = 0.0;
    int k = 1;
    for (; !trainee.finished() && k < 1'000'000; ++k) {
      trainee.read(k * dt, pose);
      trainee.write_force(Vec3::Zero());
      worst = std::max(worst, (pose.position - prev).norm());
      prev = pose.position;
      const auto foot = body.search.closest(body.body.skeleton(), pose.position);
      EXPECT_GE(foot.u, 0.3 - 0.01);
      EXPECT_LE(foot.u, 0.5 + 0.01);
      EXPECT_GE(foot.v, 0.55 - 0.01);
      EXPECT_LE(foot.v, 0.8 + 0.01);
    }
    EXPECT_TRUE(trainee.finished());
    EXPECT_LE(worst, vmax * dt * (1.0 + 1e-9));
    EXPECT_NEAR(trainee.finish_time(), trainee.scan_duration(), 1e-9);
    session::Event e;
    EXPECT_FALSE(trainee.pop_event(e));  // felt nothing, marked nothing
  }
}

TEST(ScriptedTrainee, LightPressesStayBelowAFifthOfTheThickness) {
  scripted::ScriptedTrainee light(default_scene(), scripted::whole_top_contours(default_scene()), Style::Light, 1);
  EXPECT_LT(light.max_depth_fraction(), 0.2);
  scripted::ScriptedTrainee expert(default_scene(), scripted::whole_top_contours(default_scene()), Style::Expert, 1);
  EXPECT_GE(expert.max_depth_fraction(), 0.5);
}

}  // namespace
}  // namespace palpa
