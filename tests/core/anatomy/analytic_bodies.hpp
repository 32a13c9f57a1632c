#pragma once
// Bodies on a support whose surfaces are known in closed form, the independent truth of
// the anatomy import's tests: a dome on a plane, a cap on a curved chest wall, a slab on
// ribs. Voxelized by the voxel centre (generic labels: 1 tissue, 3 support, 4 lesion).
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include <Eigen/Geometry>

#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/mat_fit.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/vec3.hpp"

namespace palpa::anatomy::testing {

struct Ball {
  Vec3 centre;
  double radius;
};

struct AnalyticBody {
  std::function<double(double, double)> support;  ///< z (m) of the support's surface
  std::function<double(double, double)> skin;     ///< z (m) of the free surface where above the support
  double half_x, half_y;                          ///< m: the volume spans [-half, half] in x and y
  double z_lo, z_hi;                              ///< m: and this in z
  double support_depth = 6e-3;                    ///< m of support voxels under its surface
  std::optional<Ball> lesion;

  double top(double x, double y) const { return std::max(skin(x, y), support(x, y)); }
  double thickness(double x, double y) const { return top(x, y) - support(x, y); }
  int label_at(const Vec3& p) const {
    if (lesion && (p - lesion->centre).norm() < lesion->radius) return 4;
    const double b = support(p.x(), p.y());
    if (p.z() < b) return p.z() > b - support_depth ? 3 : 0;
    return p.z() < skin(p.x(), p.y()) ? 1 : 0;
  }
};

/// A spherical cap: sphere of radius 70 mm, centre 40 mm below the plane z = 0 (30 mm high,
/// 57 mm across its base's radius).
inline AnalyticBody dome_on_plane() {
  AnalyticBody b;
  b.support = [](double, double) { return 0.0; };
  b.skin = [](double x, double y) {
    const double q = 0.07 * 0.07 - x * x - y * y;
    return q > 0.0 ? -0.04 + std::sqrt(q) : -1.0;
  };
  b.half_x = b.half_y = 0.064;
  b.z_lo = -0.010;
  b.z_hi = 0.034;
  b.lesion = Ball{Vec3(0.012, -0.008, 0.014), 0.006};
  return b;
}

/// A lens 25 mm thick at its centre, 50 mm in radius, on a chest wall curving as a cylinder
/// of 150 mm radius around y.
inline AnalyticBody cap_on_curved_wall() {
  AnalyticBody b;
  b.support = [](double x, double) { return -(0.15 - std::sqrt(0.15 * 0.15 - x * x)); };
  b.skin = [support = b.support](double x, double y) {
    const double rho2 = (x * x + y * y) / (0.05 * 0.05);
    return support(x, y) + 0.025 * (1.0 - rho2) * (rho2 < 1.0 ? 1.0 : 10.0);
  };
  b.half_x = b.half_y = 0.058;
  b.z_lo = -0.022;
  b.z_hi = 0.030;
  return b;
}

/// A slab 30 mm high, flat to 25 mm from its centre and tapering smoothly to nothing over
/// the next 40 mm (at most 50 degrees steep), on ribs: a support rising and falling 3 mm
/// with a 35 mm period along x (ribs and the spaces between them).
inline AnalyticBody slab_on_ribs() {
  AnalyticBody b;
  b.support = [](double x, double) { return 0.003 * std::sin(2.0 * M_PI * x / 0.035); };
  b.skin = [](double x, double y) {
    auto window = [](double u) {
      const double edge = std::abs(u) - 0.025;  // flat to 25 mm, down to 0 at 65 mm
      if (edge <= 0.0) return 1.0;
      if (edge >= 0.040) return 0.0;
      const double c = std::cos(0.5 * M_PI * edge / 0.040);
      return c * c;
    };
    return 0.030 * window(x) * window(y) - 0.004;
  };
  b.half_x = b.half_y = 0.066;
  b.z_lo = -0.012;
  b.z_hi = 0.030;
  return b;
}

/// The body voxelized at `voxel` (m) by the label at each voxel centre. `rotation` turns the
/// voxel grid in the world (the body stays where it is): the direction matrix of the file.
inline LabelVolume voxelize(const AnalyticBody& body, double voxel, const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  LabelVolume v;
  // A rotated grid must still hold the body: size it by the rotated box's extent.
  const Vec3 half(body.half_x, body.half_y, 0.5 * (body.z_hi - body.z_lo));
  const Vec3 centre(0.0, 0.0, 0.5 * (body.z_hi + body.z_lo));
  Vec3 extent = Vec3::Zero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) extent[r] += std::abs(rotation(c, r)) * half[c];
  }
  for (int a = 0; a < 3; ++a) {
    v.dims[static_cast<std::size_t>(a)] = static_cast<int>(std::ceil(2.0 * extent[a] / voxel)) + 1;
    v.spacing[static_cast<std::size_t>(a)] = voxel;
  }
  const Vec3 corner = centre - rotation * (0.5 * voxel * Vec3(v.dims[0] - 1, v.dims[1] - 1, v.dims[2] - 1));
  v.origin = to_array(corner);
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) v.direction[3 * r + c] = rotation(static_cast<int>(r), static_cast<int>(c));
  }
  v.labels.resize(v.voxel_count());
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        const Vec3 p = to_vec3(v.world(i, j, k));
        const bool inside_box = std::abs(p.x()) <= body.half_x && std::abs(p.y()) <= body.half_y;
        v.labels[v.index(i, j, k)] = static_cast<Label>(inside_box ? body.label_at(p) : 0);
      }
    }
  }
  return v;
}

/// m: the first-order distance from p to the surface z = f(x, y) (its gradient by central
/// differences): the vertical gap times the cosine of the slope.
inline double distance_to(const std::function<double(double, double)>& f, const Vec3& p) {
  const double e = 1e-5;
  const double gx = (f(p.x() + e, p.y()) - f(p.x() - e, p.y())) / (2 * e);
  const double gy = (f(p.x(), p.y() + e) - f(p.x(), p.y() - e)) / (2 * e);
  return std::abs(p.z() - f(p.x(), p.y())) / std::sqrt(1.0 + gx * gx + gy * gy);
}

/// True when the rim (where the thickness reaches 0) is farther than `band` (m) from (x, y)
/// along the support: every point within the band has tissue, or none has.
inline bool away_from_rim(const AnalyticBody& body, double x, double y, double band) {
  const bool inside = body.thickness(x, y) > 0.0;
  for (int a = 0; a < 16; ++a) {
    const double angle = 2.0 * M_PI * a / 16.0;
    for (double r : {0.25 * band, 0.5 * band, 0.75 * band, band}) {
      if ((body.thickness(x + r * std::cos(angle), y + r * std::sin(angle)) > 0.0) != inside) return false;
    }
  }
  return true;
}

/// How far a fitted body's contours lie from the analytic surfaces away from the rim.
struct Measured {
  double top = 0.0, bottom = 0.0;  // m, the largest distance away from the rim
  long points = 0;
  Vec3 worst_top = Vec3::Zero();
};

inline mat::MatBody geometry(const FittedBody& fitted) {
  mat::BodyGrid grid = fitted.grid;
  grid.stiffness.assign(grid.point_count(), 100.0);
  return mat::MatBody::fit(grid);
}

// Both contours sampled 6 times per grid interval, against the analytic surfaces.
inline Measured measure(const AnalyticBody& body, const FittedBody& fitted) {
  const auto mat = geometry(fitted);
  Measured out;
  const auto& u = mat.u_params();
  const auto& v = mat.v_params();
  for (std::size_t i = 0; i + 1 < u.size(); ++i) {
    for (std::size_t j = 0; j + 1 < v.size(); ++j) {
      for (int a = 0; a < 6; ++a) {
        for (int b = 0; b < 6; ++b) {
          const double uu = u[i] + (u[i + 1] - u[i]) * a / 6.0, vv = v[j] + (v[j + 1] - v[j]) * b / 6.0;
          double p[3];
          mat.top().evaluate(uu, vv, p);
          const Vec3 top(p[0], p[1], p[2]);
          mat.bottom().evaluate(uu, vv, p);
          const Vec3 bottom(p[0], p[1], p[2]);
          const double band = fitted.report.rim_band;
          if (away_from_rim(body, top.x(), top.y(), band)) {
            const double d = distance_to([&](double x, double y) { return body.top(x, y); }, top);
            if (d > out.top) out.worst_top = top;
            out.top = std::max(out.top, d);
            ++out.points;
          }
          if (away_from_rim(body, bottom.x(), bottom.y(), band)) {
            out.bottom = std::max(out.bottom, distance_to(body.support, bottom));
          }
        }
      }
    }
  }
  return out;
}

}  // namespace palpa::anatomy::testing
