#include "palpa/mat/mat_body.hpp"

#include "palpa/vec3.hpp"

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "../common/numeric.hpp"

namespace palpa::mat {
namespace {



Array3 cross(const double* a, const double* b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const double* a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// A tangent counts as vanished when it is this much shorter than the other one:
// round-off leaves ~1e-16 of the pole's coordinates in the collapsed direction.
constexpr double kDegenerate = 1e-10;

bool unit(Array3 n, double out[3]) {
  const double len = norm(n.data());
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  for (std::size_t c = 0; c < 3; ++c) out[c] = n[c] / len;
  return true;
}

}  // namespace

std::vector<double> skeleton_samples(const BodyGrid& grid, const MaterialDefaults& defaults) {
  const std::size_t n = grid.point_count();
  std::vector<double> samples(n * kSkeletonChannels);
  for (std::size_t k = 0; k < n; ++k) {
    double* s = &samples[k * kSkeletonChannels];
    s[kX] = grid.medial[k][0];
    s[kY] = grid.medial[k][1];
    s[kZ] = grid.medial[k][2];
    s[kRadius] = grid.radius[k];
    s[kStiffness] = grid.stiffness[k];
    s[kMass] = grid.mass.empty() ? defaults.mass : grid.mass[k];
    s[kDamping] = grid.damping.empty() ? 2.0 * defaults.damping_ratio * std::sqrt(s[kStiffness] * s[kMass])
                                       : grid.damping[k];
  }
  return samples;
}

bool skeleton_normal(const spline::BSplineSurface& skeleton, double u, double v, double normal[3]) {
  // Only xyz take part. First order is enough unless a tangent vanishes (a pole), where
  // the second-order Suv gives the limit direction.
  constexpr int dim = 3;
  std::array<double, 4 * dim> first{};
  skeleton.derivatives(u, v, 1, first, dim);
  const double* su = &first[spline::derivative_index(1, 0, 1, dim, 0)];
  const double* sv = &first[spline::derivative_index(0, 1, 1, dim, 0)];
  const double lu = norm(su);
  const double lv = norm(sv);
  const bool u_collapsed = lu <= kDegenerate * lv;
  const bool v_collapsed = lv <= kDegenerate * lu;
  if (!u_collapsed && !v_collapsed) {
    const Array3 n = cross(su, sv);
    if (norm(n.data()) > kDegenerate * lu * lv) return unit(n, normal);
    return false;  // tangents parallel: no normal at this point
  }
  std::array<double, 9 * dim> second{};
  skeleton.derivatives(u, v, 2, second, dim);
  const double* suv = &second[spline::derivative_index(1, 1, 2, dim, 0)];
  // A collapsed direction, e.g. Sv = 0 along a pole row at u0: Sv(u0 + h) ~ h Suv, so the
  // normal's limit from the interior is +-(Su x Suv), the sign pointing into the domain.
  if (v_collapsed && lu > 0.0) {
    const double sign = u >= skeleton.knots_u().back() ? -1.0 : 1.0;
    Array3 n = cross(su, suv);
    for (double& c : n) c *= sign;
    return unit(n, normal);
  }
  if (u_collapsed && lv > 0.0) {
    const double sign = v >= skeleton.knots_v().back() ? -1.0 : 1.0;
    Array3 n = cross(suv, sv);
    for (double& c : n) c *= sign;
    return unit(n, normal);
  }
  return false;
}

const char* to_string(Support support) { return support == Support::Bottom ? "bottom" : "free"; }
const char* to_string(ForceModel model) { return model == ForceModel::Calibrated ? "calibrated" : "paper"; }

const char* to_string(Indenter indenter) { return indenter == Indenter::Finger ? "finger" : "pad"; }

MatBody::MatBody(std::string id, Support support, std::vector<double> u, std::vector<double> v,
                 spline::BSplineSurface skeleton, spline::BSplineSurface top, spline::BSplineSurface bottom)
    : id_(std::move(id)),
      support_(support),
      u_params_(std::move(u)),
      v_params_(std::move(v)),
      skeleton_(std::move(skeleton)),
      top_(std::move(top)),
      bottom_(std::move(bottom)) {}

MatBody MatBody::fit(const BodyGrid& grid, const FitOptions& options) {
  const std::size_t n = idx(grid.rows) * idx(grid.cols);
  if (grid.rows < 2 || grid.cols < 2 || grid.medial.size() != n || grid.radius.size() != n ||
      grid.stiffness.size() != n || (!grid.damping.empty() && grid.damping.size() != n) ||
      (!grid.mass.empty() && grid.mass.size() != n)) {
    throw FitError("body '" + grid.id + "': channel sizes do not match rows * cols");
  }
  try {
    const auto samples = skeleton_samples(grid, options.defaults);
    const auto interpolator =
        spline::GridInterpolator::from_grid(samples, grid.rows, grid.cols, kSkeletonChannels, options.interpolation);
    auto skeleton = interpolator.interpolate(samples, kSkeletonChannels);
    check_material_ranges(skeleton, interpolator.u_params(), interpolator.v_params(), samples, !grid.damping.empty(),
                          !grid.mass.empty());

    // R = P + rN and S = P - rN at the data sites, with P and r the authored values.
    std::vector<double> top(n * 3);
    std::vector<double> bottom(n * 3);
    for (int i = 0; i < grid.rows; ++i) {
      for (int j = 0; j < grid.cols; ++j) {
        const std::size_t k = idx(i * grid.cols + j);
        const double r = grid.radius[k];
        double normal[3] = {0.0, 0.0, 0.0};
        if (!skeleton_normal(skeleton, interpolator.u_params()[idx(i)], interpolator.v_params()[idx(j)], normal) &&
            r != 0.0) {
          throw FitError(fmt::format("no skeleton normal at grid point ({}, {}) where the radius is not zero", i, j));
        }
        for (std::size_t c = 0; c < 3; ++c) {
          top[k * 3 + c] = grid.medial[k][c] + r * normal[c];
          bottom[k * 3 + c] = grid.medial[k][c] - r * normal[c];
        }
      }
    }
    auto top_surface = interpolator.interpolate(top, 3);
    auto bottom_surface = interpolator.interpolate(bottom, 3);
    return {grid.id,          grid.support, interpolator.u_params(),   interpolator.v_params(), std::move(skeleton),
            std::move(top_surface), std::move(bottom_surface)};
  } catch (const spline::InterpolationError& e) {
    throw FitError("body '" + grid.id + "': " + e.what());
  } catch (const FitError& e) {
    throw FitError("body '" + grid.id + "': " + e.what());
  }
}

void check_material_ranges(const spline::BSplineSurface& skeleton, const std::vector<double>& u_params,
                           const std::vector<double>& v_params, const std::vector<double>& samples,
                           bool damping_authored, bool mass_authored) {
  // Lower bounds per channel, scaled by the data. A smooth fit of a field with a kink
  // (e.g. stiffness 0 over a region) dips a little below zero next to the kink; up to 5 %
  // of the channel's largest value is tolerated, and the force and dynamics code clamps
  // such dips to 0. A larger dip means the data jump between close points: an error.
  // Mass must stay positive.
  std::array<double, kSkeletonChannels> lo{};
  std::array<double, kSkeletonChannels> hi{};
  std::array<double, kSkeletonChannels> data_min{};
  lo.fill(0.0);
  data_min.fill(std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto c = k % kSkeletonChannels;
    hi[c] = std::max(hi[c], std::abs(samples[k]));
    data_min[c] = std::min(data_min[c], samples[k]);
  }
  const std::array<double, kSkeletonChannels> limit{
      0, 0, 0, -0.05 * hi[kRadius], -0.05 * hi[kStiffness], -0.05 * hi[kDamping], 1e-3 * data_min[kMass]};
  constexpr int kSub = 4;
  const char* names[] = {"x", "y", "z", "radius", "stiffness", "damping", "mass"};
  const char* units[] = {"m", "m", "m", "m", "N/m", "N s/m", "kg"};
  std::array<double, kSkeletonChannels> value{};
  const int m = static_cast<int>(u_params.size());
  const int n = static_cast<int>(v_params.size());
  for (int i = 0; i < m; ++i) {
    for (int si = 0; si < (i + 1 < m ? kSub : 1); ++si) {
      const double u = i + 1 < m ? u_params[idx(i)] + (u_params[idx(i + 1)] - u_params[idx(i)]) * si / kSub : 1.0;
      for (int j = 0; j < n; ++j) {
        for (int sj = 0; sj < (j + 1 < n ? kSub : 1); ++sj) {
          const double v = j + 1 < n ? v_params[idx(j)] + (v_params[idx(j + 1)] - v_params[idx(j)]) * sj / kSub : 1.0;
          skeleton.evaluate(u, v, value);
          for (std::size_t c = kRadius; c < kSkeletonChannels; ++c) {
            if (value[c] >= limit[c] && std::isfinite(value[c])) continue;
            if ((c == kDamping && !damping_authored) || (c == kMass && !mass_authored)) continue;
            throw FitError(fmt::format(
                "{} falls to {:.4g} {} between the data sites near grid point ({}, {}) (u = {:.4f}, v = {:.4f}): "
                "the spline overshoots where neighbouring values jump; smooth the field or space the points "
                "further apart",
                names[c], value[c], units[c], si * 2 < kSub ? i : i + 1, sj * 2 < kSub ? j : j + 1, u, v));
          }
        }
      }
    }
  }
}

std::size_t MatBody::memory_bytes() const {
  return sizeof(*this) + id_.capacity() + (u_params_.capacity() + v_params_.capacity()) * sizeof(double) +
         skeleton_.memory_bytes() + top_.memory_bytes() + bottom_.memory_bytes() -
         3 * sizeof(spline::BSplineSurface);  // the surfaces' own sizeof is inside sizeof(*this)
}

}  // namespace palpa::mat
