// The shared Table 1 scenes: the paper's body and MAT point counts, valid cases that fit,
// and a scripted finger that is over (and pressed into) the body it is visiting.
#include <gtest/gtest.h>

#include "palpa/scene/table1_scenes.hpp"

namespace palpa::scene {
namespace {

TEST(Table1Scenes, CountsMatchThePapersRows) {
  const auto& scenes = table1_scenes();
  ASSERT_EQ(scenes.size(), 6U);
  const int bodies[] = {1, 1, 4, 10, 17, 35};
  const int points[] = {49, 105, 213, 309, 465, 927};  // Table 1 of Corso et al. 2002
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const auto file = make_table1_case(scenes[k]);
    EXPECT_EQ(scenes[k].bodies, bodies[k]);
    EXPECT_EQ(static_cast<int>(file.bodies.size()), bodies[k]);
    int n = 0;
    for (const auto& g : file.bodies) n += static_cast<int>(g.medial.size());
    EXPECT_EQ(n, points[k]);
  }
}

TEST(Table1Scenes, FingerPressesIntoTheBodyItVisits) {
  const auto& spec = table1_scenes()[2];  // 4 bodies
  const auto scene = Scene::build(make_table1_case(spec), "table1");
  ASSERT_EQ(scene.size(), 4U);
  // Visit k lasts 0.25 s; at its start the finger is 15 mm in front of the dome's top
  // (cos 9t) at 8 + 6 sin 5t mm below z = 3 cm, so it is inside body k mod 4.
  for (int visit = 0; visit < 6; ++visit) {
    const double t = 0.25 * visit + 0.01;
    const Vec3 q = table1_probe(spec.bodies, t);
    const auto body = static_cast<std::size_t>(visit % spec.bodies);
    EXPECT_NEAR(q.x(), 0.12 * static_cast<double>(body), 0.0151) << "t " << t;
    EXPECT_LT(q.z(), 0.03);
    auto state = scene.make_state();
    const auto hit = scene.probe(q, state);
    EXPECT_EQ(hit.body, static_cast<int>(body)) << "t " << t;
    EXPECT_GT(hit.contact.depth, 0.0) << "t " << t;  // pressed in (2-14 mm below z = 3 cm; shallow at times)
  }
}

}  // namespace
}  // namespace palpa::scene
