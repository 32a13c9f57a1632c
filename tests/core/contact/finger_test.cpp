// The rounded finger (contact/finger.hpp, docs/model.md "A rounded finger"): Sneddon's
// sphere and its Hertz limit, the bonded-layer factor, and a case pressed by a finger
// against the neo-Hookean finite-element curves of data/reference.
#include "palpa/contact/finger.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <numbers>
#include <fstream>
#include <string>
#include <vector>

#include "palpa/author/presets.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"
#include "../support/reference_curves.hpp"

namespace palpa::contact {
namespace {

constexpr double kR = kFingertipRadius;

TEST(Finger, SneddonsContactRadiusInvertsItsDepthAndTendsToHertz) {
  for (const double d : {1e-6, 1e-4, 1e-3, 4e-3, 8e-3, 1.2e-2, 3e-2}) {
    const double c = sphere_contact_radius(d, kR);
    ASSERT_GT(c, 0.0);
    ASSERT_LT(c, kR);
    EXPECT_NEAR(0.5 * c * std::log((kR + c) / (kR - c)), d, 1e-12 * kR) << d;
  }
  // Small depth: c -> sqrt(R d) (Hertz); Sneddon's sphere is softer-edged, so c stays below it.
  EXPECT_NEAR(sphere_contact_radius(1e-6, kR) / std::sqrt(kR * 1e-6), 1.0, 1e-4);
  EXPECT_LT(sphere_contact_radius(4e-3, kR), std::sqrt(kR * 4e-3));
  EXPECT_EQ(sphere_contact_radius(0.0, kR), 0.0);
  EXPECT_EQ(sphere_contact_radius(-1e-3, kR), 0.0);
}

TEST(Finger, OnAThickLayerAShallowPressIsHertz) {
  // F = 4/3 E / (1 - nu^2) sqrt(R) d^1.5 (Hertz 1882) where the layer is deep and the press
  // small (D -> 1, no softening to speak of). Hertz takes the sphere as a paraboloid, so
  // Sneddon's exact sphere falls below it as the contact grows: 0.27 % at 0.2 mm.
  const double E = 5000.0, nu = 0.49;
  for (const double d : {1e-6, 1e-5, 5e-5}) {
    const double hertz = 4.0 / 3.0 * E / (1.0 - nu * nu) * std::sqrt(kR) * std::pow(d, 1.5);
    EXPECT_NEAR(finger_force(E, nu, d, 10.0, {}) / hertz, 1.0, 1e-3) << d;
  }
  const double at_02 = 4.0 / 3.0 * E / (1.0 - nu * nu) * std::sqrt(kR) * std::pow(2e-4, 1.5);
  EXPECT_LT(finger_force(E, nu, 2e-4, 10.0, {}), at_02);
}

TEST(Finger, TheBondedLayerFactorStartsAtOneAndGrowsAsTheLayerThins) {
  for (const double nu : {0.3, 0.45, 0.49}) {
    EXPECT_DOUBLE_EQ(bonded_sphere_factor(0.0, nu), 1.0);
    double last = 1.0;
    for (int k = 1; k <= 20; ++k) {
      const double d = bonded_sphere_factor(0.05 * k, nu);
      EXPECT_GT(d, last) << nu << " " << 0.05 * k;
      last = d;
    }
  }
  // Dimitriadis et al.'s first-order term for a bonded, nearly incompressible layer:
  // 1 - 2 a0 chi / pi with a0 = -1.7473 at nu = 0.49.
  EXPECT_NEAR((bonded_sphere_factor(1e-4, 0.49) - 1.0) / 1e-4, 2.0 * 1.7473 / std::numbers::pi, 1e-3);
  // A more compressible layer is stiffened less by its base.
  EXPECT_LT(bonded_sphere_factor(0.3, 0.3), bonded_sphere_factor(0.3, 0.49));
}

using reference_test::centre_press;
using reference_test::reference_force;

scene::Scene slab(double thickness, mat::Indenter indenter) {
  io::CaseFile file = author::make_modulus_slab(0.12, thickness, 5000.0, mat::ForceModel::Calibrated);
  file.indenter = indenter;
  return scene::Scene::build(io::parse_case(io::to_json(file).dump(), "slab.json"), "slab.json");
}

TEST(Finger, ACaseInKpaPressedByAFingerFollowsTheNeoHookeanFem) {
  // Both finger curves (8 mm sphere, frictionless, neo-Hookean with NLGEOM; 40 mm to 9.5 mm
  // and 20 mm to 8 mm, i.e. 40 % of the layer): within 10 % at every depth from 0.5 mm.
  struct Curve { const char* file; double thickness, reach; };
  for (const Curve c : {Curve{"slab40_E5k_finger8_neohooke.csv", 0.040, 0.0095},
                        Curve{"slab20_E5k_finger8_neohooke.csv", 0.020, 0.0080}}) {
    const auto scene = slab(c.thickness, mat::Indenter::Finger);
    EXPECT_EQ(scene.indenter(), mat::Indenter::Finger);
    double worst = 0.0;
    for (int k = 1; k * 0.0005 <= c.reach + 1e-9; ++k) {
      const double d = k * 0.0005;
      const double fem = reference_force(c.file, d);
      ASSERT_TRUE(std::isfinite(fem)) << c.file << " " << d;
      const double error = centre_press(scene, d) / fem - 1.0;
      EXPECT_LE(std::abs(error), 0.10) << c.file << " at " << d;
      worst = std::max(worst, std::abs(error));
    }
    std::printf("finger on %s: worst force error %.1f %%\n", c.file, 100.0 * worst);
  }
}

TEST(Finger, AFingerFeelsSofterThanThePadAtFirstAndGrowsStifferWithThePress) {
  // What a rounded finger changes: the force starts like depth^1.5 (a small contact that
  // grows), not linearly; the pad's flat punch is the stiffer at every clinical depth here.
  const auto pad = slab(0.040, mat::Indenter::Pad);
  const auto finger = slab(0.040, mat::Indenter::Finger);
  const double f1 = centre_press(finger, 0.001), f2 = centre_press(finger, 0.002), f4 = centre_press(finger, 0.004);
  EXPECT_NEAR(std::log(f4 / f2) / std::log(2.0), 1.5, 0.15);  // about Hertz's exponent
  EXPECT_GT(f2 / f1, 2.4);
  EXPECT_LT(centre_press(finger, 0.002), 0.5 * centre_press(pad, 0.002));
  // A body in N/m keeps the paper's springs whatever the indenter says.
  io::CaseFile springs = author::make_preset_case(author::preset_defaults(author::Preset::Slab), "slab");
  const auto plain = scene::Scene::build(springs, "slab.json");
  springs.indenter = mat::Indenter::Finger;
  const auto with_finger = scene::Scene::build(springs, "slab.json");
  EXPECT_DOUBLE_EQ(centre_press(with_finger, 0.004), centre_press(plain, 0.004));
}

TEST(Finger, TheCaseFieldIsReadWrittenAndCheckedByName) {
  io::CaseFile file = author::make_modulus_slab(0.12, 0.04, 5000.0, mat::ForceModel::Calibrated);
  EXPECT_FALSE(io::to_json(file).contains("indenter"));  // the pad is the default: nothing written
  file.indenter = mat::Indenter::Finger;
  const auto doc = io::to_json(file);
  EXPECT_EQ(doc["indenter"], "finger");
  EXPECT_EQ(io::parse_case(doc.dump(), "f.json").indenter, mat::Indenter::Finger);
  auto bad = doc;
  bad["indenter"] = "thumb";
  try {
    (void)io::parse_case(bad.dump(), "bad.json");
    ADD_FAILURE() << "an unknown indenter was accepted";
  } catch (const io::CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: /indenter: indenter must be \"pad\" or \"finger\""),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace palpa::contact
