#pragma once
// The Novint Falcon as R. E. Stamper's delta robot ("A three degree of freedom parallel
// manipulator with only translational degrees of freedom", PhD thesis, University of
// Maryland, 1997; the model libnifalcon uses for the Falcon).
//
// Each leg i is turned by phi_i about the device's axis; in the leg's frame
//   u = cos(phi) x + sin(phi) y - r,   v = -sin(phi) x + cos(phi) y - s,   w = z
// the motor turns the thigh (length a) by theta_i in the u-w plane, and the shin
// parallelogram (length b, joint offsets d and e, effector offsets c and f) closes the loop:
//   v = b cos(t3) - f,   L = d + e + b sin(t3),
//   (u + c - a cos(theta))^2 + (w - a sin(theta))^2 = L^2.
// Inverse kinematics (position -> motor angles) is closed form; forward kinematics (motor
// angles -> position) solves the three loop equations by Newton's method; the Jacobian
// dp/dtheta comes from differentiating them, and the motor torques for a force F at the
// grip are J^T F (virtual work).
//
// Constants: the Falcon's dimensions as libnifalcon publishes them since release 1.0.1
// (2009-09-20; unchanged in 1.1 and since) in include/falcon/core/FalconGeometry.h ("values
// refer to a diagram from R.E. Stamper, page 30"): a = 0.060, b = 0.1025, c = 0.01443,
// d = e = 0.01125, f = -0.025, r = 0.0400, s = -0.02309 (m). Release 1.0 had c = 0.014,
// r = 0.037233758, s = -0.027330909 (Palpa's values until this correction). libnifalcon
// commit 5ca9c0bf36a1 ("Corrected values of r and s ... Tested", N. Begley, authored
// 2009-06-23) set c = 0.01443, r = 0.02309, s = -0.0400, and commit 935a31eade4f ("Flipped
// r/s values for geometry based on advice from Steven Martin", 2009-09-18) swapped r and s
// to the values above; 1.0.1 shipped both. For the same thigh angles, 1.0's dimensions put
// the grip up to 3.75 mm from where these do over the workspace sphere (1.9 mm at its
// centre; tests/device/falcon_kinematics_test.cpp).
// Legs at phi = 90, -30 and -150 degrees, each plus a 15-degree tilt of the axes. Encoders:
// 320-slot wheel read in quadrature (1280 counts per motor turn), motor shaft 14.25 mm
// driving an arm drum of 110 mm, and an encoder count of 0 at a thigh angle of 35 degrees
// (FalconGeometry.h and FalconKinematic.h::getTheta). Torque to firmware units: 10,000 per
// N m of thigh torque with the sign reversed (libnifalcon FalconKinematicStamper::getForces),
// and the firmware takes at most +-4096.
// Device frame (m): x right, y up, z toward the user, origin on the device's axis.
#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>
#include "palpa/vec3.hpp"

namespace palpa::device::falcon {

using Mat3 = Eigen::Matrix3d;

struct Geometry {
  double a = 0.060, b = 0.1025, c = 0.01443, d = 0.01125, e = 0.01125, f = -0.025;
  double r = 0.0400, s = -0.02309;
  std::array<double, 3> phi{};  ///< rad, filled by the constructor of Kinematics
};

/// Motor angles (rad) of the three thighs.
using Angles = Eigen::Vector3d;

class Kinematics {
 public:
  Kinematics();
  const Geometry& geometry() const { return g_; }

  /// Closed form; empty when the position is out of reach.
  std::optional<Angles> inverse(const Vec3& position) const;
  /// Newton's method from `guess` (the last position: at 1 kHz it is a few micrometres
  /// off, so two or three steps reach 1e-12 m). Empty when it does not converge, or
  /// converges to a point whose inverse() is not `angles` (angles no arm can take).
  std::optional<Vec3> forward(const Angles& angles, const Vec3& guess) const;
  /// J = dp/dtheta at `position` (m per rad); empty out of reach or at a singularity.
  std::optional<Mat3> jacobian(const Vec3& position) const;
  /// Thigh torques (N m) that push the grip with `force` (N) at `position`: J^T F.
  std::optional<Vec3> torques(const Vec3& position, const Vec3& force) const;

  /// The middle of the workspace (m): the thighs at about -24..63 degrees over the sphere
  /// of kWorkspaceRadius around it, the Jacobian well conditioned (condition number < 2.8).
  static Vec3 workspace_center() { return Vec3(0.0, 0.0, 0.12); }
  /// Radius (m) of the sphere around workspace_center() the grip reaches (about 0.04: docs/devices.md).
  static constexpr double kWorkspaceRadius = 0.04;

 private:
  /// Loop equation of leg i and its derivatives with respect to p and theta.
  double loop(int leg, const Vec3& p, double theta, Vec3* dp, double* dtheta) const;
  Geometry g_;
};

/// Encoder counts <-> thigh angles (rad).
double encoder_to_angle(std::int16_t count);
/// Firmware torque units for a thigh torque (N m), before the +-4096 limit.
double torque_to_units(double torque);
inline constexpr double kMaxTorqueUnits = 4096.0;

}  // namespace palpa::device::falcon
