#include "palpa/mat/layer_stiffness.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace palpa::mat {
namespace {

// 8-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 8> kNodes{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                       -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                       0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                         0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                         0.2223810344533745, 0.1012285362903763};

// M(u) = 1 - L(u): how much stiffer the bonded layer's surface is than the half-space's at
// Hankel wavenumber u / h (c = 3 - 4 nu). Written with exp(-2u) factored out so that it
// neither overflows nor cancels at large u, where it decays like u^2 exp(-2u).
double layer_weight(double u, double nu) {
  const double c = 3.0 - 4.0 * nu;
  const double e = std::exp(-2.0 * u);
  const double e4 = e * e;
  const double num = c * (1.0 - e4) - 4.0 * u * e;
  const double den = c * (1.0 + e4) + (1.0 + c * c + 4.0 * u * u) * e;
  return 1.0 - num / den;
}

// Gauss-Legendre rule of `panels` x 8 points on [a, b].
void composite_rule(double a, double b, int panels, Eigen::VectorXd& x, Eigen::VectorXd& w) {
  x.resize(panels * 8);
  w.resize(panels * 8);
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    for (int k = 0; k < 8; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      x[p * 8 + k] = a + width * (p + 0.5 * (kNodes[ku] + 1.0));
      w[p * 8 + k] = 0.5 * width * kWeights[ku];
    }
  }
}

}  // namespace

double bonded_layer_factor(double a_over_h, double nu) {
  if (!(a_over_h >= 0.0 && a_over_h <= 10.0)) {
    throw std::invalid_argument(fmt::format("bonded_layer_factor: a/h must be in [0, 10], got {:f}", a_over_h));
  }
  if (!(nu >= 0.0 && nu < 0.5)) {
    throw std::invalid_argument(fmt::format("bonded_layer_factor: Poisson's ratio must be in [0, 0.5), got {:f}", nu));
  }
  if (a_over_h == 0.0) return 1.0;  // the half-space
  const double lam = a_over_h;
  // Nystrom on x, y in [0, 1]:  psi(x) - (2 lam / pi) int_0^1 k(x, y) psi(y) dy = 1,
  // kappa = int_0^1 psi, with k(x, y) = int_0^inf M(u) cos(lam u x) cos(lam u y) du.
  // M has decayed below 1e-15 by u = 20. The panels in u are narrow enough that each holds
  // at most about one period of cos(lam u x) (8 points per panel then integrate it to
  // 1e-8); a thin layer (large lam) needs more of them, and more in x for psi's edge.
  const int x_panels = lam <= 1.0 ? 2 : 4;
  const int u_panels = std::max(40, static_cast<int>(std::ceil(20.0 * lam / 3.0)) * 2);
  Eigen::VectorXd x, wx, u, wu;
  composite_rule(0.0, 1.0, x_panels, x, wx);
  composite_rule(0.0, 20.0, u_panels, u, wu);
  Eigen::MatrixXd c(x.size(), u.size());  // cos(lam u_j x_i)
  Eigen::VectorXd m(u.size());            // M(u_j) times the u rule's weight
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    m[j] = layer_weight(u[j], nu) * wu[j];
    for (Eigen::Index i = 0; i < x.size(); ++i) c(i, j) = std::cos(lam * u[j] * x[i]);
  }
  const Eigen::MatrixXd k = c * m.asDiagonal() * c.transpose();
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(x.size(), x.size());
  a -= (2.0 * lam / std::numbers::pi) * k * wx.asDiagonal();
  const Eigen::VectorXd psi = a.partialPivLu().solve(Eigen::VectorXd::Ones(x.size()));
  return wx.dot(psi);
}

namespace {

void check_modulus(double modulus) {
  if (!(modulus >= 0.0) || !std::isfinite(modulus)) {
    throw std::invalid_argument("layer_stiffness: the modulus must be a finite number >= 0 Pa");
  }
}

void check_pad(double pad_radius) {
  if (!(pad_radius > 0.0) || !std::isfinite(pad_radius)) {
    throw std::invalid_argument("layer_stiffness: the pad radius must be a finite number > 0 m");
  }
}

// a/h with the thickness floored at the pad radius (a non-finite thickness too).
double pad_over_thickness(double pad_radius, double thickness) {
  return pad_radius / (std::isfinite(thickness) ? std::max(thickness, pad_radius) : pad_radius);
}

}  // namespace

double layer_stiffness(double modulus, double nu, double pad_radius, double thickness) {
  check_modulus(modulus);
  check_pad(pad_radius);
  return 2.0 * pad_radius * modulus * bonded_layer_factor(pad_over_thickness(pad_radius, thickness), nu) /
         (1.0 - nu * nu);
}

LayerStiffnessTable::LayerStiffnessTable(double nu, double pad_radius) : nu_(nu), pad_radius_(pad_radius) {
  check_pad(pad_radius);
  for (int k = 0; k <= kIntervals; ++k) {
    kappa_[static_cast<std::size_t>(k)] = bonded_layer_factor(static_cast<double>(k) / kIntervals, nu);
  }
}

double LayerStiffnessTable::operator()(double modulus, double thickness) const {
  check_modulus(modulus);
  const double t = pad_over_thickness(pad_radius_, thickness) * kIntervals;  // in [0, kIntervals]
  // The four nodes around t (shifted inwards at the ends), Lagrange weights over them.
  const int first = std::clamp(static_cast<int>(std::floor(t)) - 1, 0, kIntervals - 3);
  double kappa = 0.0;
  for (int a = 0; a < 4; ++a) {
    double w = 1.0;
    for (int b = 0; b < 4; ++b) {
      if (b != a) w *= (t - (first + b)) / static_cast<double>(a - b);
    }
    kappa += w * kappa_[static_cast<std::size_t>(first + a)];
  }
  return 2.0 * pad_radius_ * modulus * kappa / (1.0 - nu_ * nu_);
}

std::vector<double> layer_stiffness_field(const std::vector<double>& modulus, const std::vector<double>& radius,
                                          double nu) {
  const LayerStiffnessTable layer(nu, kFingertipPadRadius);
  std::vector<double> k(modulus.size());
  for (std::size_t p = 0; p < k.size(); ++p) k[p] = layer(modulus[p], 2.0 * radius[p]);
  return k;
}

}  // namespace palpa::mat
