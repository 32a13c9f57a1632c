// View-frustum culling: the box test against frusta whose planes are written by hand.
#include <gtest/gtest.h>

#include <array>

#include "palpa/render/frustum.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/live/display_meshes.hpp"

namespace {

using palpa::render::Frustum;
using V = Eigen::Vector3d;

// The cube |x|, |y|, |z| <= 1 as six inward planes.
Frustum unit_cube() {
  return Frustum({1, 0, 0, 1, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 0, 1, 1, 0, 0, -1, 1});
}

// A camera at the origin looking down -z with a 90 degree field of view (|x| <= -z,
// |y| <= -z), near plane z = -1, far plane z = -10.
Frustum perspective() {
  return Frustum({1, 0, -1, 0, -1, 0, -1, 0, 0, 1, -1, 0, 0, -1, -1, 0, 0, 0, -1, -1, 0, 0, 1, 10});
}

TEST(Frustum, BoxesInsideStraddlingAndBehindOnePlane) {
  const auto f = unit_cube();
  EXPECT_TRUE(f.may_see(V(-0.5, -0.5, -0.5), V(0.5, 0.5, 0.5)));
  EXPECT_TRUE(f.may_see(V(0.9, -0.1, -0.1), V(3.0, 0.1, 0.1)));    // straddles x = 1
  EXPECT_TRUE(f.may_see(V(1.0, 0.0, 0.0), V(2.0, 1.0, 1.0)));      // touches x = 1
  EXPECT_FALSE(f.may_see(V(1.001, -0.1, -0.1), V(3.0, 0.1, 0.1))); // beyond x = 1
  EXPECT_FALSE(f.may_see(V(-0.1, -0.1, -9.0), V(0.1, 0.1, -1.5))); // beyond z = -1
  EXPECT_TRUE(f.may_see(V(-5, -5, -5), V(5, 5, 5)));               // encloses the cube
}

TEST(Frustum, PerspectiveViewSeesWhatIsInFrontWithinTheFieldOfView) {
  const auto f = perspective();
  EXPECT_TRUE(f.may_see(V(-0.1, -0.1, -5.1), V(0.1, 0.1, -4.9)));  // straight ahead
  EXPECT_FALSE(f.may_see(V(-0.1, -0.1, 4.9), V(0.1, 0.1, 5.1)));   // behind the camera
  EXPECT_FALSE(f.may_see(V(-0.1, -0.1, -12), V(0.1, 0.1, -11)));   // beyond the far plane
  // At z = -5 the view reaches |x| <= 5: a box at x in [5.2, 6] is outside the right plane,
  // one at [4.8, 6] straddles it.
  EXPECT_FALSE(f.may_see(V(5.2, -0.1, -5.1), V(6.0, 0.1, -4.9)));
  EXPECT_TRUE(f.may_see(V(4.8, -0.1, -5.1), V(6.0, 0.1, -4.9)));
  EXPECT_FALSE(f.may_see(V(-0.1, -6.0, -5.1), V(0.1, -5.2, -4.9)));
}

TEST(Frustum, NeverCullsABoxThatReachesIntoTheVolume) {
  const auto f = unit_cube();
  int wrongly_culled = 0;
  // Property: a box that contains a point of the cube is never culled.
  for (double x = -1.0; x <= 1.0; x += 0.25)
    for (double y = -1.0; y <= 1.0; y += 0.25)
      for (double z = -1.0; z <= 1.0; z += 0.25)
        if (!f.may_see(V(x - 0.01, y - 0.3, z), V(x + 2.0, y, z + 0.5))) ++wrongly_culled;
  EXPECT_EQ(wrongly_culled, 0);
}

TEST(DisplayMeshesCulling, AnInvisibleBodyKeepsItsMeshAndCatchesUpWhenSeenAgain) {
  const auto file = palpa::io::load_case(std::string(PALPA_SOURCE_DIR) + "/data/cases/two-bodies.json");
  const auto scene = palpa::scene::Scene::build(file, "two-bodies.json");
  ASSERT_EQ(scene.size(), 2u);
  palpa::live::DisplayMeshes meshes(scene);
  const auto rest_z = meshes.top(1).positions[2];

  // A snapshot with both bodies at version 1, body 1 lifted by exactly 1 cm.
  palpa::engine::SceneSnapshot shot;
  shot.bodies.resize(2);
  for (std::size_t b = 0; b < 2; ++b) {
    // The engine's drawn nets: the rest contours refined for display.
    const auto net = palpa::deform::display_net(scene.body(b).body, palpa::engine::EngineOptions{}.deform);
    const auto& top = net.top.control();
    const auto& bottom = net.bottom.control();
    shot.bodies[b].version = 1;
    shot.bodies[b].top.assign(top.begin(), top.end());
    shot.bodies[b].bottom.assign(bottom.begin(), bottom.end());
  }
  for (std::size_t k = 2; k < shot.bodies[1].top.size(); k += 3) shot.bodies[1].top[k] += 0.01;

  meshes.set_visible(1, false);
  EXPECT_EQ(meshes.update(shot), 1u);  // body 0 only
  EXPECT_TRUE(meshes.changed(0));
  EXPECT_FALSE(meshes.changed(1));
  EXPECT_EQ(meshes.version(1), 0u);
  EXPECT_EQ(meshes.top(1).positions[2], rest_z);

  meshes.set_visible(1, true);
  EXPECT_EQ(meshes.update(shot), 1u);  // body 1 catches up; body 0 is current
  EXPECT_FALSE(meshes.changed(0));
  EXPECT_TRUE(meshes.changed(1));
  EXPECT_EQ(meshes.version(1), 1u);
  EXPECT_NEAR(meshes.top(1).positions[2], rest_z + 0.01F, 1e-6);
}

}  // namespace
