// The Falcon's delta-robot kinematics: inverse and forward agree over the whole workspace,
// the Jacobian matches finite differences of the forward kinematics, and the torques do
// the work the force does (virtual work).
#include <gtest/gtest.h>

#include <cmath>

#include "palpa/device/falcon_kinematics.hpp"

namespace palpa::device::falcon {
namespace {

// Points on a grid over the workspace sphere (and its centre).
std::vector<Vec3> workspace_points() {
  std::vector<Vec3> points;
  const double r = Kinematics::kWorkspaceRadius;
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      for (int k = -4; k <= 4; ++k) {
        const Vec3 d(r * i / 4.0, r * j / 4.0, r * k / 4.0);
        if (d.norm() <= r) points.push_back(Kinematics::workspace_center() + d);
      }
    }
  }
  return points;
}

TEST(FalconKinematics, InverseThenForwardReturnsThePointEverywhereInTheWorkspace) {
  const Kinematics kin;
  const auto points = workspace_points();
  ASSERT_GT(points.size(), 250u);
  double worst = 0.0;
  for (const auto& p : points) {
    const auto angles = kin.inverse(p);
    ASSERT_TRUE(angles) << p.transpose();
    // Angles a real Falcon's thighs reach (libnifalcon sees them within about -30..80 degrees).
    for (int k = 0; k < 3; ++k) {
      EXPECT_GT((*angles)[k], -0.7) << p.transpose();
      EXPECT_LT((*angles)[k], 1.4) << p.transpose();
    }
    // From the centre, as the driver does when it starts (and from a guess 2 cm off).
    const auto q = kin.forward(*angles, Kinematics::workspace_center());
    ASSERT_TRUE(q) << p.transpose();
    worst = std::max(worst, (*q - p).norm());
    const auto q2 = kin.forward(*angles, p + Vec3(0.02, -0.01, 0.01));
    ASSERT_TRUE(q2);
    worst = std::max(worst, (*q2 - p).norm());
    // And back: the angles of the found position are the angles we started from.
    EXPECT_LT((*kin.inverse(*q) - *angles).norm(), 1e-9);
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(FalconKinematics, ReachIsLimited) {
  const Kinematics kin;
  EXPECT_FALSE(kin.inverse(Vec3(0.0, 0.0, 0.5)));  // half a metre out: no arm reaches
  EXPECT_FALSE(kin.inverse(Vec3(0.3, 0.0, 0.12)));
  EXPECT_FALSE(kin.jacobian(Vec3(0.0, 0.0, 0.5)));
}

TEST(FalconKinematics, ForwardFindsNoGripForAnglesNoArmCanTake) {
  // Thighs at 144, -74 and 144 degrees (encoder counts 3000, -3000, 3000): from about two
  // in five of these guesses Newton's method used to settle on a point where a shin is
  // stretched past its length (loop() clamps it) and return it as the grip. The driver must
  // see no position there: it counts the misses and reports the fault.
  const Kinematics kin;
  const Angles impossible(encoder_to_angle(3000), encoder_to_angle(-3000), encoder_to_angle(3000));
  for (const auto& guess : workspace_points()) {
    EXPECT_FALSE(kin.forward(impossible, guess)) << guess.transpose();
  }
  // A whole turn of a thigh is the same pose: still found.
  const Vec3 p = Kinematics::workspace_center() + Vec3(0.01, 0.02, -0.01);
  Angles turned = *kin.inverse(p);
  turned[1] += 2.0 * 3.14159265358979323846;
  const auto q = kin.forward(turned, Kinematics::workspace_center());
  ASSERT_TRUE(q);
  EXPECT_LT((*q - p).norm(), 1e-12);
}

TEST(FalconKinematics, TheJacobianIsTheDerivativeOfTheForwardKinematics) {
  const Kinematics kin;
  const double h = 1e-6;  // rad
  for (const auto& p : workspace_points()) {
    const auto jac = kin.jacobian(p);
    ASSERT_TRUE(jac);
    const Angles a = *kin.inverse(p);
    Mat3 numeric;
    for (int j = 0; j < 3; ++j) {
      Angles plus = a, minus = a;
      plus[j] += h;
      minus[j] -= h;
      numeric.col(j) = (*kin.forward(plus, p) - *kin.forward(minus, p)) / (2.0 * h);
    }
    // Central differences: error ~h^2 times the third derivative, far below 1e-6 m/rad.
    EXPECT_LT((numeric - *jac).norm(), 1e-6 * std::max(1.0, jac->norm())) << p.transpose();
  }
}

TEST(FalconKinematics, TorquesDoTheWorkOfTheForce) {
  const Kinematics kin;
  const Vec3 p = Kinematics::workspace_center() + Vec3(0.01, -0.015, 0.02);
  const Vec3 force(1.5, -2.0, 4.0);
  const Vec3 tau = *kin.torques(p, force);
  // Virtual work: a small motion of the thighs d(theta) moves the grip by dp, and
  // tau . dtheta = F . dp.
  const Angles a = *kin.inverse(p);
  const Angles dtheta(1e-7, -2e-7, 1.5e-7);
  const Vec3 dp = *kin.forward(a + dtheta, p) - p;
  EXPECT_NEAR(tau.dot(dtheta), force.dot(dp), 1e-12);
  // On the axis, straight up or down, all three motors share the load equally.
  const Vec3 axis = Kinematics::workspace_center();
  const Vec3 up = *kin.torques(axis, Vec3(0.0, 8.0, 0.0));
  const Vec3 out = *kin.torques(axis, Vec3(0.0, 0.0, 8.0));
  EXPECT_NEAR(out[0], out[1], 1e-12);
  EXPECT_NEAR(out[1], out[2], 1e-12);
  EXPECT_GT(std::abs(up[0] - up[1]) + std::abs(up[1] - up[2]), 1e-3);  // a load across the axis does not
  // 8 N, the Falcon's maximum, needs less than the firmware's +-4096 on every motor.
  EXPECT_LT(std::abs(torque_to_units(out[0])), kMaxTorqueUnits);
}

TEST(FalconKinematics, EncoderCountsToThighAngles) {
  // 0 counts: 35 degrees. One motor turn (1280 counts) turns the 110 mm drum by the
  // 14.25 mm shaft's circumference: 360 * 14.25 / 110 = 46.636... degrees.
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  EXPECT_NEAR(encoder_to_angle(0), 35.0 * kDeg, 1e-15);
  EXPECT_NEAR(encoder_to_angle(1280) - encoder_to_angle(0), 360.0 * 14.25 / 110.0 * kDeg, 1e-12);
  EXPECT_NEAR(encoder_to_angle(-1280) - encoder_to_angle(0), -360.0 * 14.25 / 110.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(torque_to_units(0.1), -1000.0);
}

}  // namespace
}  // namespace palpa::device::falcon
