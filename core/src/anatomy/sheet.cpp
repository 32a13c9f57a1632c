#include "sheet.hpp"

#include "palpa/mat/mat_body.hpp"
#include "palpa/spline/interpolation.hpp"

namespace palpa::anatomy {

SiteResidual site_residual(const SurfacePair& pair, double s, double t, const Vec3& nl, const Site& x) {
  SiteResidual out;
  double ht = 0.0, gts = 0.0, gtt = 0.0, hb = 0.0, gbs = 0.0, gbt = 0.0;
  if (!pair.top.sample(s + x.r * nl.x(), t + x.r * nl.y(), ht, gts, gtt)) return out;
  if (!pair.bottom.sample(s - x.r * nl.x(), t - x.r * nl.y(), hb, gbs, gbt)) return out;
  out.f1 = x.m + x.r * nl.z() - ht;
  out.f2 = x.m - x.r * nl.z() - hb;
  out.d1 = nl.z() - (gts * nl.x() + gtt * nl.y());
  out.d2 = -nl.z() + (gbs * nl.x() + gbt * nl.y());
  out.ok = true;
  return out;
}

std::vector<double> skeleton_xyz(const SurfacePair& pair, const Sheet& sheet) {
  std::vector<double> xyz(sheet.sites.size() * 3);
  for (int i = 0; i < sheet.rows; ++i) {
    for (int j = 0; j < sheet.cols; ++j) {
      const std::size_t k = sheet.at(i, j);
      const Vec3 p = pair.frame.to_world(sheet.s[static_cast<std::size_t>(i)], sheet.t[static_cast<std::size_t>(j)],
                                         sheet.sites[k].m);
      for (std::size_t c = 0; c < 3; ++c) xyz[k * 3 + c] = p[static_cast<Eigen::Index>(c)];
    }
  }
  return xyz;
}

std::vector<Vec3> site_normals(const SurfacePair& pair, const Sheet& sheet) {
  const auto xyz = skeleton_xyz(pair, sheet);
  const auto interp = spline::GridInterpolator::from_grid(xyz, sheet.rows, sheet.cols, 3);
  const auto skeleton = interp.interpolate(xyz, 3);
  std::vector<Vec3> normals(sheet.sites.size(), Vec3::UnitZ());
  for (int i = 0; i < sheet.rows; ++i) {
    for (int j = 0; j < sheet.cols; ++j) {
      double nw[3] = {0.0, 0.0, 1.0};
      if (!mat::skeleton_normal(skeleton, interp.u_params()[static_cast<std::size_t>(i)],
                                interp.v_params()[static_cast<std::size_t>(j)], nw)) {
        continue;
      }
      const Vec3 world(nw[0], nw[1], nw[2]);
      Vec3 local(world.dot(pair.frame.e1), world.dot(pair.frame.e2), world.dot(pair.frame.n));
      if (local.z() < 0.0) local = -local;
      normals[sheet.at(i, j)] = local;
    }
  }
  return normals;
}

}  // namespace palpa::anatomy
