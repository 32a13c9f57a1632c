#pragma once
// B-spline basis functions on a clamped knot vector (The NURBS Book, chapter 2).
#include <span>

namespace palpa::spline {

/// Highest degree the evaluators support; their scratch space lives on the stack
/// so that evaluation never allocates (it runs in the haptic thread).
inline constexpr int kMaxDegree = 7;

/// A2.1 FindSpan: the knot span index s with knots[s] <= u < knots[s+1], for a curve
/// with `control_points` control points of degree p. u at or beyond the right end maps
/// to the last non-empty span, u at or before the left end to the first.
int find_span(int control_points, int p, double u, std::span<const double> knots);

/// A2.2 BasisFuns: the p+1 non-vanishing basis functions N[span-p .. span] at u into n.
void basis_functions(int span, double u, int p, std::span<const double> knots, double* n);

/// A2.3 DersBasisFuns: the non-vanishing basis functions and their derivatives up to
/// order d at u. ders[k*(p+1) + j] = k-th derivative of N[span-p+j]. Orders above p are 0.
void basis_function_derivatives(int span, double u, int p, int d, std::span<const double> knots,
                                double* ders);

}  // namespace palpa::spline
