#include "palpa/mat/layer_stiffness.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

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

// Gauss-Legendre rule of `panels` x 8 points on [a, b], appended to x and w.
void composite_rule(double a, double b, int panels, Eigen::VectorXd& x, Eigen::VectorXd& w) {
  const Eigen::Index start = x.size();
  x.conservativeResize(start + panels * 8);
  w.conservativeResize(start + panels * 8);
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    for (int k = 0; k < 8; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      x[start + p * 8 + k] = a + width * (p + 0.5 * (kNodes[ku] + 1.0));
      w[start + p * 8 + k] = 0.5 * width * kWeights[ku];
    }
  }
}

// Hayes et al.'s integral equation, by Nystrom on x, y in [0, 1]:
//   psi(x) - (2 lam / pi) int_0^1 k(x, y) psi(y) dy = 1,   kappa = int_0^1 psi,
//   k(x, y) = int_0^inf M(u) cos(lam u x) cos(lam u y) du,
// with lam = a / h, u = xi h and M(u) = weight(u) the surface's extra stiffness over the
// half-space's at wavenumber xi; the u integral by the rule (u, wu) of 8-point panels, the
// kernel summed panel by panel so that a long rule needs no large matrix.
template <class Weight>
double nystrom_factor(double lam, int x_panels, const Eigen::VectorXd& u, const Eigen::VectorXd& wu,
                      const Weight& weight) {
  Eigen::VectorXd x, wx;
  composite_rule(0.0, 1.0, x_panels, x, wx);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(x.size(), x.size());
  Eigen::MatrixXd c(x.size(), 8);  // cos(lam u_j x_i) over one panel
  Eigen::VectorXd m(8);            // M(u_j) times the u rule's weight
  for (Eigen::Index p = 0; p < u.size(); p += 8) {
    for (Eigen::Index j = 0; j < 8; ++j) {
      m[j] = weight(u[p + j]) * wu[p + j];
      for (Eigen::Index i = 0; i < x.size(); ++i) c(i, j) = std::cos(lam * u[p + j] * x[i]);
    }
    k.noalias() += c * m.asDiagonal() * c.transpose();
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(x.size(), x.size());
  a -= (2.0 * lam / std::numbers::pi) * k * wx.asDiagonal();
  const Eigen::VectorXd psi = a.partialPivLu().solve(Eigen::VectorXd::Ones(x.size()));
  return wx.dot(psi);
}

// Panels in u narrow enough that each holds at most about one period of cos(lam u x) (8
// points per panel then integrate it to 1e-8), and at least 40 over [from, to].
int u_panels(double lam, double from, double to) {
  return std::max(40, static_cast<int>(std::ceil(lam * (to - from) / 3.0)) * 2);
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
  // M has decayed below 1e-15 by u = 20; a thin layer (large lam) needs more panels in u,
  // and more in x for psi's edge.
  Eigen::VectorXd u, wu;
  composite_rule(0.0, 20.0, u_panels(lam, 0.0, 20.0), u, wu);
  return nystrom_factor(lam, lam <= 1.0 ? 2 : 4, u, wu, [nu](double v) { return layer_weight(v, nu); });
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

// A layered column: the same integral equation with the layered column's surface compliance
// in place of the homogeneous layer's. In each layer (Love's strain function; Timoshenko and
// Goodier, Theory of Elasticity, 3rd ed., 1970) the Hankel transform at wavenumber xi of an
// axisymmetric state is
// phi = J0(xi r) f(z), f = (A + B s) exp(s - tau) + (C + D s) exp(-s), with s = xi z the local
// depth, tau = xi t the layer's thickness (both exponentials <= 1 in the layer, so nothing
// overflows at large xi), and, with xi = 1 (the ratio to the half-space is scale-free):
//   2 G u_r = f',  2 G u_z = (1 - 2 nu) f'' - 2 (1 - nu) f,
//   sigma_z = (1 - nu) f''' - (2 - nu) f',  tau_rz = nu f'' + (1 - nu) f.
// One layer, or equal layers, give Hayes' M(u) above to 1e-10 (tests/reference/fem checks M, core.ColumnModulus the moduli).
namespace {

// Rows u_r, u_z, sigma_z, tau_rz per unit of A, B, C, D at local depth s of a layer of
// thickness tau and shear modulus g.
Eigen::Matrix4d layer_state(double s, double tau, double g, double nu) {
  const double p = std::exp(s - tau);
  const double e = std::exp(-s);
  Eigen::Matrix4d f;  // rows f, f', f'', f'''
  f << p, s * p,         e,  s * e,
       p, (1.0 + s) * p, -e, (1.0 - s) * e,
       p, (2.0 + s) * p, e,  (s - 2.0) * e,
       p, (3.0 + s) * p, -e, (3.0 - s) * e;
  Eigen::Matrix4d out;
  out.row(0) = f.row(1) / (2.0 * g);
  out.row(1) = ((1.0 - 2.0 * nu) * f.row(2) - 2.0 * (1.0 - nu) * f.row(0)) / (2.0 * g);
  out.row(2) = (1.0 - nu) * f.row(3) - (2.0 - nu) * f.row(1);
  out.row(3) = nu * f.row(2) + (1.0 - nu) * f.row(0);
  return out;
}

// M(u) of the column: 1 - its surface compliance at u = xi h over that of a half-space of the
// top layer's modulus, 2 (1 - nu^2) / (E_1 xi). Unit pressure and no shear at the skin (a
// frictionless pad), all four of u_r, u_z, sigma_z, tau_rz continuous at each bonded
// interface, u_r = u_z = 0 on the rigid base: 4 n equations for the 4 n coefficients.
double column_weight(double u, const std::vector<TissueLayer>& layers, double total, double nu) {
  const auto n = static_cast<Eigen::Index>(layers.size());
  const auto tau = [&](Eigen::Index i) { return u * layers[static_cast<std::size_t>(i)].thickness / total; };
  const auto g = [&](Eigen::Index i) { return layers[static_cast<std::size_t>(i)].modulus / (2.0 * (1.0 + nu)); };
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4 * n, 4 * n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(4 * n);
  const Eigen::Matrix4d skin = layer_state(0.0, tau(0), g(0), nu);
  a.block<2, 4>(0, 0) = skin.bottomRows<2>();
  b[0] = 1.0;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    a.block<4, 4>(2 + 4 * i, 4 * i) = layer_state(tau(i), tau(i), g(i), nu);
    a.block<4, 4>(2 + 4 * i, 4 * i + 4) = -layer_state(0.0, tau(i + 1), g(i + 1), nu);
  }
  a.block<2, 4>(4 * n - 2, 4 * n - 4) = layer_state(tau(n - 1), tau(n - 1), g(n - 1), nu).topRows<2>();
  const Eigen::VectorXd coefficients = a.partialPivLu().solve(b);
  const double w = skin.row(1).dot(coefficients.head<4>());
  return 1.0 - std::abs(w) * layers.front().modulus / (2.0 * (1.0 - nu * nu));
}

// The layers with a thickness > 0, after checking every value.
std::vector<TissueLayer> checked_layers(std::span<const TissueLayer> layers, double nu, double pad_radius) {
  if (layers.empty()) throw std::invalid_argument("column_modulus: no layers");
  if (!(nu >= 0.0 && nu < 0.5)) {
    throw std::invalid_argument(fmt::format("column_modulus: Poisson's ratio must be in [0, 0.5), got {:f}", nu));
  }
  check_pad(pad_radius);
  std::vector<TissueLayer> kept;
  for (const TissueLayer& l : layers) {
    if (!(l.thickness >= 0.0 && l.modulus >= 0.0) || !std::isfinite(l.thickness) || !std::isfinite(l.modulus)) {
      throw std::invalid_argument(fmt::format("column_modulus: a layer of {} m at {} Pa; both must be finite and >= 0",
                                              l.thickness, l.modulus));
    }
    if (l.thickness > 0.0) kept.push_back(l);
  }
  if (kept.empty()) throw std::invalid_argument("column_modulus: the total thickness must be > 0");
  return kept;
}

// Springs in series, thickness-weighted: a thin compressible column's uniaxial-strain limit.
double series_modulus(const std::vector<TissueLayer>& layers, double total) {
  double compliance = 0.0;
  for (const TissueLayer& l : layers) compliance += l.thickness / (total * l.modulus);
  return 1.0 / compliance;
}

}  // namespace

double column_modulus(std::span<const TissueLayer> layers_from_skin, double nu, double pad_radius) {
  const std::vector<TissueLayer> layers = checked_layers(layers_from_skin, nu, pad_radius);
  double total = 0.0;
  double softest = std::numeric_limits<double>::infinity();
  for (const TissueLayer& l : layers) {
    total += l.thickness;
    softest = std::min(softest, l.modulus);
  }
  if (layers.size() == 1) return layers.front().modulus;
  if (softest == 0.0) return 0.0;  // a layer that carries nothing: the pad sinks
  const double lam = pad_radius / total;
  if (lam > 10.0) return series_modulus(layers, total);
  // u = xi h. The base is felt below u ~ 20 (Hayes' range); the shallowest interface, at the
  // top layer's thickness t1, until exp(-2 u t1 / h) has decayed too, so the rule runs on to
  // u = 20 h / t1 (t1 floored at h / 200: a thinner skin is integrated to u = 4000 only).
  const double tail = 20.0 * std::min(total / layers.front().thickness, 200.0);
  Eigen::VectorXd u, wu;
  composite_rule(0.0, 20.0, u_panels(lam, 0.0, 20.0), u, wu);
  if (tail > 20.0) composite_rule(20.0, tail, u_panels(lam, 20.0, tail), u, wu);
  const double column = nystrom_factor(lam, 4, u, wu, [&](double v) { return column_weight(v, layers, total, nu); });
  // The homogeneous factor on the same rule, so that equal moduli give the modulus itself.
  const double homogeneous = nystrom_factor(lam, 4, u, wu, [nu](double v) { return layer_weight(v, nu); });
  return layers.front().modulus * column / homogeneous;
}

}  // namespace palpa::mat
