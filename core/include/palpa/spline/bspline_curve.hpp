#pragma once
// Non-rational B-spline curve with control points of any dimension.
#include <span>
#include <vector>

namespace palpa::spline {

class BSplineCurve {
 public:
  /// control: control_points * dim values, point i at [i*dim, (i+1)*dim).
  /// Throws std::invalid_argument when the knot vector does not fit the degree and count.
  BSplineCurve(int degree, std::vector<double> knots, int dim, std::vector<double> control);

  int degree() const { return degree_; }
  int dim() const { return dim_; }
  int control_points() const { return static_cast<int>(control_.size()) / dim_; }
  const std::vector<double>& knots() const { return knots_; }
  const std::vector<double>& control() const { return control_; }

  /// C(u) into out[0..dim). u is clamped to the knot range.
  void evaluate(double u, std::span<double> out) const;

  /// A3.2 CurveDerivsAlg1: out[k*dim + c] = k-th derivative of channel c, k = 0..d.
  void derivatives(double u, int d, std::span<double> out) const;

 private:
  int degree_;
  int dim_;
  std::vector<double> knots_;
  std::vector<double> control_;
};

}  // namespace palpa::spline
