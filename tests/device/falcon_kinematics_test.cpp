// The Falcon's delta-robot kinematics: inverse and forward agree over the whole workspace,
// the Jacobian matches finite differences of the forward kinematics, and the torques do
// the work the force does (virtual work). The last group checks all of it against a second,
// independent model of the mechanism written here (each leg as an open chain of joints,
// closed by a generic solver), with the dimensions of libnifalcon 1.0.1 typed in again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/LU>
#include <Eigen/Eigenvalues>

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
    // Checked again with the corrected dimensions of libnifalcon 1.0.1 (the header's
    // comment): over the sphere the thighs now turn through -24..63 degrees (-25..61 with
    // 1.0's), well inside these bounds, so the bounds stay.
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
  // 8 N straight out, the Falcon's maximum, needs less than the firmware's +-4096 on every
  // motor: about 2,008 units with libnifalcon 1.0.1's dimensions (1,974 with 1.0's; the
  // bound holds for both, so it is unchanged).
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

// ---------------------------------------------------------------------------------------
// A second model of the mechanism, written from the mechanism and not from
// falcon_kinematics.cpp, to check Palpa's kinematics against. Each leg is an open chain of
// joints in the device frame, and a pose of the grip is whatever closes all three chains.
// Leg i is turned by phi_i about the device's axis; its unit vectors are u_i (radial),
// v_i (along the motor's axis) and w (the device's z). From the hip H_i = r u_i + s v_i the
// thigh (length a, motor angle theta) reaches the knee
//   K = H_i + a (cos(theta) u_i + sin(theta) w);
// the shin parallelogram, its sides b at an angle t3 to the motor's axis, its joint offsets
// d and e, swung by theta2 in the u-w plane, reaches the effector's joint
//   Q = K + (d + e + b sin(t3)) (cos(theta2) u_i + sin(theta2) w) + b cos(t3) v_i,
// which sits at c u_i + f v_i from the grip P (Stamper's thesis, the figure on page 30,
// with libnifalcon's names for the dimensions).

struct Dims {
  double a, b, c, d, e, f, r, s;
};
// libnifalcon 1.0.1 (2009-09-20; unchanged in 1.1 and on its master branch since), typed in
// again here rather than read from Palpa's Geometry, so that a wrong constant there shows.
// c from commit 5ca9c0bf (N. Begley, "Corrected values of r and s ... Tested", 2009-06-23),
// r and s as commit 935a31ea (2009-09-18) then swapped them ("Flipped r/s values for
// geometry based on advice from Steven Martin"); 5ca9c0bf's own r = 0.02309, s = -0.0400
// were in no release.
constexpr Dims kLibnifalcon101{0.060, 0.1025, 0.01443, 0.01125, 0.01125, -0.025, 0.0400, -0.02309};
// libnifalcon 1.0 (2009-09-06), which Palpa used before: c, r and s differ.
constexpr Dims kLibnifalcon10{0.060, 0.1025, 0.014, 0.01125, 0.01125, -0.025, 0.037233758, -0.027330909};

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

struct LegFrame {
  Vec3 u, v, w;
};

// Legs at 90, -30 and -150 degrees, each turned 15 degrees further (the axes' tilt).
LegFrame leg_frame(int leg) {
  const double phi = (90.0 - 120.0 * leg + 15.0) * kDegree;
  return {Vec3(std::cos(phi), std::sin(phi), 0.0), Vec3(-std::sin(phi), std::cos(phi), 0.0), Vec3::UnitZ()};
}

Vec3 knee_of(const Dims& g, const LegFrame& l, double theta) {
  return g.r * l.u + g.s * l.v + g.a * (std::cos(theta) * l.u + std::sin(theta) * l.w);
}

// The grip at the end of leg `leg`'s chain.
Vec3 chain_end(const Dims& g, int leg, double theta, double theta2, double t3) {
  const LegFrame l = leg_frame(leg);
  const Vec3 joint = knee_of(g, l, theta) +
                     (g.d + g.e + g.b * std::sin(t3)) * (std::cos(theta2) * l.u + std::sin(theta2) * l.w) +
                     g.b * std::cos(t3) * l.v;
  return joint - g.c * l.u - g.f * l.v;
}

// With the thigh at theta and the grip at `grip`: what separates the knee from the
// effector's joint across the motor's axis, less what the parallelogram spans across it
// when its sides make up the separation along the axis. Zero when the leg closes.
double shin_gap(const Dims& g, int leg, const Vec3& grip, double theta) {
  const LegFrame l = leg_frame(leg);
  const Vec3 span = grip + g.c * l.u + g.f * l.v - knee_of(g, l, theta);
  const double along = span.dot(l.v);
  const double across = (span - along * l.v).norm();
  const double t3 = std::acos(std::clamp(along / g.b, -1.0, 1.0));
  return across - (g.d + g.e + g.b * std::sin(t3));
}

// The thigh angle of one leg for the grip at `grip`: a scan of -90..90 degrees (where a
// Falcon's thigh can be) for a sign change of shin_gap, then bisection to the last bit.
// Empty unless the scan finds exactly one root: then there is no choice of branch to make.
std::optional<double> solve_thigh(const Dims& g, int leg, const Vec3& grip) {
  constexpr int kSteps = 360;
  const double step = kPi / kSteps;
  std::optional<double> bracket;
  for (int k = 0; k < kSteps; ++k) {
    const double t = -kPi / 2.0 + k * step;
    if ((shin_gap(g, leg, grip, t) > 0.0) == (shin_gap(g, leg, grip, t + step) > 0.0)) continue;
    if (bracket) return std::nullopt;
    bracket = t;
  }
  if (!bracket) return std::nullopt;
  double lo = *bracket, hi = *bracket + step;
  const bool lo_positive = shin_gap(g, leg, grip, lo) > 0.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    ((shin_gap(g, leg, grip, mid) > 0.0) == lo_positive ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::optional<Angles> solve_angles(const Dims& g, const Vec3& grip) {
  Angles out;
  for (int leg = 0; leg < 3; ++leg) {
    const auto theta = solve_thigh(g, leg, grip);
    if (!theta) return std::nullopt;
    out[leg] = *theta;
  }
  return out;
}

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

// x = (grip, theta2 and t3 of leg 0, of leg 1, of leg 2): each chain's end less the grip.
Vec9 chain_residual(const Dims& g, const Angles& theta, const Vec9& x) {
  Vec9 out;
  for (int leg = 0; leg < 3; ++leg) {
    out.segment<3>(3 * leg) =
        chain_end(g, leg, theta[leg], x[3 + 2 * leg], x[4 + 2 * leg]) - Vec3(x.head<3>());
  }
  return out;
}

// The grip for the thigh angles theta: Newton's method on all nine unknowns of the three
// chains, its Jacobian by central differences, from the grip at `guess` with each shin
// square to its motor's axis and swung toward the guess. Empty when it does not converge,
// or converges to a parallelogram folded the wrong way (sin(t3) < 0).
std::optional<Vec3> solve_grip(const Dims& g, const Angles& theta, const Vec3& guess) {
  Vec9 x;
  x.head<3>() = guess;
  for (int leg = 0; leg < 3; ++leg) {
    const LegFrame l = leg_frame(leg);
    const Vec3 span = guess + g.c * l.u + g.f * l.v - knee_of(g, l, theta[leg]);
    x[3 + 2 * leg] = std::atan2(span.dot(l.w), span.dot(l.u));
    x[4 + 2 * leg] = kPi / 2.0;
  }
  constexpr double h = 1e-7;
  for (int iteration = 0; iteration < 100; ++iteration) {
    Mat9 jac;
    for (int j = 0; j < 9; ++j) {
      const Vec9 dx = h * Vec9::Unit(j);
      jac.col(j) = (chain_residual(g, theta, x + dx) - chain_residual(g, theta, x - dx)) / (2.0 * h);
    }
    const Vec9 step = jac.fullPivLu().solve(chain_residual(g, theta, x));
    x -= step;
    if (!x.allFinite()) return std::nullopt;
    if (step.norm() < 1e-15) {
      for (int leg = 0; leg < 3; ++leg) {
        if (!(std::sin(x[4 + 2 * leg]) > 0.0)) return std::nullopt;
      }
      return Vec3(x.head<3>());
    }
  }
  return std::nullopt;
}

// Poses drawn uniformly from the workspace sphere (a fixed seed: the same poses each run).
std::vector<Vec3> random_poses(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<Vec3> poses;
  while (static_cast<int>(poses.size()) < count) {
    const Vec3 d(coordinate(rng), coordinate(rng), coordinate(rng));
    if (d.norm() <= 1.0) poses.push_back(Kinematics::workspace_center() + Kinematics::kWorkspaceRadius * d);
  }
  return poses;
}

// Points spread evenly over the workspace sphere's surface (a Fibonacci lattice).
std::vector<Vec3> sphere_surface(int count) {
  std::vector<Vec3> points;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count;
    const double ring = std::sqrt(1.0 - y * y);
    const Vec3 d(ring * std::cos(golden * i), y, ring * std::sin(golden * i));
    points.push_back(Kinematics::workspace_center() + Kinematics::kWorkspaceRadius * d);
  }
  return points;
}

TEST(FalconKinematicsIndependent, TheDimensionsAreLibnifalcon101s) {
  // Palpa used libnifalcon 1.0's dimensions until libnifalcon's later correction came to
  // light (c, r and s: see kLibnifalcon101); the same thigh angles put the grip up to
  // 3.75 mm apart under the two sets (TheOldDimensionsPutTheGripUpTo4MillimetresElsewhere).
  const Kinematics kinematics;
  const Geometry& g = kinematics.geometry();  // a reference into an object that outlives the checks
  const Dims& want = kLibnifalcon101;
  EXPECT_EQ(g.a, want.a);
  EXPECT_EQ(g.b, want.b);
  EXPECT_EQ(g.c, want.c);
  EXPECT_EQ(g.d, want.d);
  EXPECT_EQ(g.e, want.e);
  EXPECT_EQ(g.f, want.f);
  EXPECT_EQ(g.r, want.r);
  EXPECT_EQ(g.s, want.s);
  for (int leg = 0; leg < 3; ++leg) {
    EXPECT_NEAR(g.phi[static_cast<std::size_t>(leg)], (90.0 - 120.0 * leg + 15.0) * kDegree, 1e-15) << leg;
  }
}

TEST(FalconKinematicsIndependent, InverseAgreesWithTheChainsSolvedByBisection) {
  const Kinematics kin;
  auto poses = random_poses(500, 1997);
  for (const auto& p : workspace_points()) poses.push_back(p);
  double worst_angle = 0.0, worst_grip = 0.0;
  for (const auto& p : poses) {
    const auto palpa_angles = kin.inverse(p);
    const auto chain_angles = solve_angles(kLibnifalcon101, p);
    ASSERT_TRUE(palpa_angles) << p.transpose();
    ASSERT_TRUE(chain_angles) << p.transpose() << ": not exactly one thigh angle in -90..90 degrees";
    worst_angle = std::max(worst_angle, (*palpa_angles - *chain_angles).cwiseAbs().maxCoeff());
    // Palpa's angles close the three chains at p.
    const auto grip = solve_grip(kLibnifalcon101, *palpa_angles, Kinematics::workspace_center());
    ASSERT_TRUE(grip) << p.transpose();
    worst_grip = std::max(worst_grip, (*grip - p).norm());
  }
  EXPECT_LT(worst_angle, 1e-12);  // rad
  EXPECT_LT(worst_grip, 1e-12);   // m
}

TEST(FalconKinematicsIndependent, ForwardOfInverseIsThePointOnRandomPoses) {
  const Kinematics kin;
  double worst = 0.0;
  for (const auto& p : random_poses(500, 2009)) {
    // From the centre, as the driver starts; and from the chains' angles, not Palpa's own.
    const auto from_inverse = kin.forward(*kin.inverse(p), Kinematics::workspace_center());
    const auto from_chains = kin.forward(*solve_angles(kLibnifalcon101, p), Kinematics::workspace_center());
    ASSERT_TRUE(from_inverse) << p.transpose();
    ASSERT_TRUE(from_chains) << p.transpose();
    worst = std::max({worst, (*from_inverse - p).norm(), (*from_chains - p).norm()});
  }
  EXPECT_LT(worst, 1e-12);  // m
}

TEST(FalconKinematicsIndependent, TorquesAreTheTransposeOfTheChainsJacobian) {
  // Virtual work: the thighs turned by dtheta move the grip by dp = J dtheta, and torques
  // tau do the force F's work, tau . dtheta = F . dp for every dtheta, so tau = J^T F. Here
  // J comes from central differences of the chains' forward solve, not from Palpa.
  const Kinematics kin;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> component(-8.0, 8.0);  // N
  double worst_jacobian = 0.0, worst_torque = 0.0;
  for (const auto& p : random_poses(100, 1280)) {
    const Angles theta = *solve_angles(kLibnifalcon101, p);
    constexpr double h = 1e-6;  // rad
    Mat3 numeric;
    for (int j = 0; j < 3; ++j) {
      const Vec3 dtheta = h * Vec3::Unit(j);
      const auto plus = solve_grip(kLibnifalcon101, theta + dtheta, p);
      const auto minus = solve_grip(kLibnifalcon101, theta - dtheta, p);
      ASSERT_TRUE(plus && minus) << p.transpose();
      numeric.col(j) = (*plus - *minus) / (2.0 * h);
    }
    const Vec3 force(component(rng), component(rng), component(rng));
    const auto jac = kin.jacobian(p);
    const auto tau = kin.torques(p, force);
    ASSERT_TRUE(jac && tau) << p.transpose();
    worst_jacobian = std::max(worst_jacobian, (*jac - numeric).cwiseAbs().maxCoeff());
    worst_torque = std::max(worst_torque, (*tau - numeric.transpose() * force).cwiseAbs().maxCoeff());
  }
  // Entries of J are up to about 0.1 m/rad; differences over h = 1e-6 rad are good to
  // about 1e-10 m/rad (h^2 times the third derivative, and the solve's rounding over 2h).
  EXPECT_LT(worst_jacobian, 1e-9);  // m/rad
  EXPECT_LT(worst_torque, 1e-8);    // N m, for forces up to 8 N a component
}

TEST(FalconKinematicsIndependent, TheWorkspaceIsWhatTheHeaderSays) {
  // falcon_kinematics.hpp: over the workspace sphere the thighs stay within about
  // -24..63 degrees and J's condition number below 2.8 (-25..61 and 2.84 with libnifalcon
  // 1.0's dimensions).
  const Kinematics kin;
  auto poses = sphere_surface(2000);
  for (const auto& p : random_poses(500, 35)) poses.push_back(p);
  double lowest = 1.0, highest = 0.0, worst_condition = 0.0;
  for (const auto& p : poses) {
    const Angles theta = *kin.inverse(p);
    lowest = std::min(lowest, theta.minCoeff());
    highest = std::max(highest, theta.maxCoeff());
    // Condition number: the ratio of J's largest singular value to its smallest, the square
    // root of the ratio of J^T J's eigenvalues (in increasing order).
    const Mat3 jac = *kin.jacobian(p);
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(jac.transpose() * jac);
    worst_condition = std::max(worst_condition, std::sqrt(eigen.eigenvalues()[2] / eigen.eigenvalues()[0]));
  }
  EXPECT_GT(lowest, -24.5 * kDegree);
  EXPECT_LT(highest, 63.5 * kDegree);
  EXPECT_LT(worst_condition, 2.8);
}

TEST(FalconKinematicsIndependent, TheOldDimensionsPutTheGripUpTo4MillimetresElsewhere) {
  // Why the change matters: the thigh angles that libnifalcon 1.0's dimensions give for a
  // grip at p (the chains solved with kLibnifalcon10) are, read with the corrected
  // dimensions, a grip about 1.9 mm nearer the device at the centre and up to 3.75 mm off
  // on the sphere's surface (the largest differences are there). With the old dimensions
  // still in Palpa these differences would be 0.
  const Kinematics kin;
  const Vec3 centre = Kinematics::workspace_center();
  const Vec3 shift = *kin.forward(*solve_angles(kLibnifalcon10, centre), centre) - centre;
  EXPECT_NEAR(shift.x(), 0.0, 1e-9);
  EXPECT_NEAR(shift.y(), 0.0, 1e-9);
  EXPECT_NEAR(shift.z(), -1.93e-3, 0.01e-3);
  double largest = 0.0;
  for (const auto& p : sphere_surface(2000)) {
    const auto angles = solve_angles(kLibnifalcon10, p);
    ASSERT_TRUE(angles) << p.transpose();
    largest = std::max(largest, (*kin.forward(*angles, p) - p).norm());
  }
  EXPECT_GT(largest, 3.70e-3);
  EXPECT_LT(largest, 3.76e-3);
}

}  // namespace
}  // namespace palpa::device::falcon
