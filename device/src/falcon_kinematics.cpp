#include "palpa/device/falcon_kinematics.hpp"

#include <cmath>

#include <Eigen/LU>

namespace palpa::device::falcon {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kTilt = kPi / 12.0;  // 15 degrees: each leg's axis is tilted off the desk plane
}  // namespace

Kinematics::Kinematics() { g_.phi = {kPi / 2.0 + kTilt, -kPi / 6.0 + kTilt, -5.0 * kPi / 6.0 + kTilt}; }

double Kinematics::loop(int leg, const Vec3& p, double theta, Vec3* dp, double* dtheta) const {
  const double cp = std::cos(g_.phi[static_cast<std::size_t>(leg)]);
  const double sp = std::sin(g_.phi[static_cast<std::size_t>(leg)]);
  const double u = cp * p.x() + sp * p.y() - g_.r;
  const double v = -sp * p.x() + cp * p.y() - g_.s;
  const double w = p.z();
  const double cos3 = (v + g_.f) / g_.b;
  const double sin3 = std::sqrt(std::max(0.0, 1.0 - cos3 * cos3));
  const double len = g_.d + g_.e + g_.b * sin3;
  const double du = u + g_.c - g_.a * std::cos(theta);
  const double dw = w - g_.a * std::sin(theta);
  if (dp) {
    // dL/dv = b d(sin t3)/dv = -cos3 / sin3
    const double dlen_dv = sin3 > 0.0 ? -cos3 / sin3 : 0.0;
    const double gu = 2.0 * du;
    const double gv = -2.0 * len * dlen_dv;
    *dp = Vec3(gu * cp - gv * sp, gu * sp + gv * cp, 2.0 * dw);
  }
  if (dtheta) *dtheta = 2.0 * du * g_.a * std::sin(theta) - 2.0 * dw * g_.a * std::cos(theta);
  return du * du + dw * dw - len * len;
}

std::optional<Angles> Kinematics::inverse(const Vec3& p) const {
  Angles out;
  for (int i = 0; i < 3; ++i) {
    const double cp = std::cos(g_.phi[static_cast<std::size_t>(i)]);
    const double sp = std::sin(g_.phi[static_cast<std::size_t>(i)]);
    const double u = cp * p.x() + sp * p.y() - g_.r;
    const double v = -sp * p.x() + cp * p.y() - g_.s;
    const double w = p.z();
    const double cos3 = (v + g_.f) / g_.b;
    if (!(std::abs(cos3) < 1.0)) return std::nullopt;
    const double len = g_.d + g_.e + g_.b * std::sqrt(1.0 - cos3 * cos3);
    // A cos(theta) + B sin(theta) = K, from expanding the loop equation.
    const double uc = u + g_.c;
    const double big_a = 2.0 * g_.a * uc;
    const double big_b = 2.0 * g_.a * w;
    const double k = uc * uc + w * w + g_.a * g_.a - len * len;
    const double rho = std::hypot(big_a, big_b);
    if (!(rho > 0.0) || std::abs(k) > rho) return std::nullopt;
    // Two knee positions close the loop; the Falcon's is the root with the smaller angle
    // (about 24 degrees at the middle of the workspace; the encoders' zero, 35 degrees, is
    // on the axis about 15 mm nearer the user; the other root folds the thigh back through
    // the base, beyond 140 degrees everywhere in the workspace).
    out[i] = std::atan2(big_b, big_a) - std::acos(k / rho);
  }
  return out;
}

std::optional<Vec3> Kinematics::forward(const Angles& angles, const Vec3& guess) const {
  Vec3 p = guess;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Vec3 residual;
    Mat3 jac;
    for (int i = 0; i < 3; ++i) {
      Vec3 grad;
      residual[i] = loop(i, p, angles[i], &grad, nullptr);
      jac.row(i) = grad.transpose();
    }
    const Eigen::PartialPivLU<Mat3> lu(jac);
    if (!(std::abs(lu.determinant()) > 1e-30)) return std::nullopt;
    const Vec3 step = lu.solve(residual);
    p -= step;
    if (!p.allFinite()) return std::nullopt;
    if (step.norm() < 1e-13) {
      // Newton also settles where no arm is: where loop() clamps a shin past its reach
      // (|cos t3| > 1) or on the knee folded back through the base. Only a point whose
      // inverse gives these angles back (up to whole turns) is the grip.
      const auto back = inverse(p);
      if (!back) return std::nullopt;
      for (int i = 0; i < 3; ++i) {
        if (!(std::abs(std::remainder((*back)[i] - angles[i], 2.0 * kPi)) < 1e-9)) return std::nullopt;
      }
      return p;
    }
  }
  return std::nullopt;
}

std::optional<Mat3> Kinematics::jacobian(const Vec3& position) const {
  const auto angles = inverse(position);
  if (!angles) return std::nullopt;
  // Each loop equation g_i(p, theta_i) = 0: dtheta_i/dp = -(dg_i/dp) / (dg_i/dtheta_i).
  Mat3 dtheta_dp;
  for (int i = 0; i < 3; ++i) {
    Vec3 grad;
    double dtheta = 0.0;
    loop(i, position, (*angles)[i], &grad, &dtheta);
    if (!(std::abs(dtheta) > 1e-15)) return std::nullopt;
    dtheta_dp.row(i) = -grad.transpose() / dtheta;
  }
  const Eigen::PartialPivLU<Mat3> lu(dtheta_dp);
  if (!(std::abs(lu.determinant()) > 1e-30)) return std::nullopt;
  return Mat3(lu.inverse());
}

std::optional<Vec3> Kinematics::torques(const Vec3& position, const Vec3& force) const {
  const auto jac = jacobian(position);
  if (!jac) return std::nullopt;
  return Vec3(jac->transpose() * force);
}

double encoder_to_angle(std::int16_t count) {
  constexpr double kCountsPerMotorTurn = 320.0 * 4.0;
  constexpr double kGear = 0.01425 / 0.110;  // shaft diameter over arm drum diameter
  constexpr double kZero = 35.0 * kPi / 180.0;
  return kZero + 2.0 * kPi * kGear * static_cast<double>(count) / kCountsPerMotorTurn;
}

double torque_to_units(double torque) { return -10000.0 * torque; }

}  // namespace palpa::device::falcon
