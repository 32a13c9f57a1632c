#include "support_model.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "palpa/anatomy/import_error.hpp"

namespace palpa::anatomy {

Frame frame_with_normal(const Vec3& origin, const Vec3& normal) {
  Frame f;
  f.origin = origin;
  f.n = normal.normalized();
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (std::abs(f.n[a]) < std::abs(f.n[axis]) - 1e-9) axis = a;
  }
  const Vec3 along = Vec3::Unit(axis);
  f.e1 = (along - along.dot(f.n) * f.n).normalized();
  f.e2 = f.n.cross(f.e1);
  return f;
}

Frame plane_frame(const std::vector<Vec3>& points, const Vec3& inside) {
  if (points.size() < 3) throw ImportError("the support has fewer than 3 points next to the tissue");
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) cov += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  // Eigenvalues ascending: the smallest spread is the normal; the middle one must be real.
  if (!(eig.eigenvalues()[1] > 1e-12 * std::max(eig.eigenvalues()[2], 1e-300))) {
    throw ImportError("the support's points next to the tissue lie on a line, not a surface");
  }
  Vec3 n = eig.eigenvectors().col(0);
  if (n.dot(inside - centre) < 0.0) n = -n;
  return frame_with_normal(centre, n);
}

SupportModel fit_support(const std::vector<Vec3>& points, const Vec3& inside, double resolution) {
  SupportModel model;
  model.frame = plane_frame(points, inside);
  const auto count = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd a(count, 6);
  Eigen::VectorXd h(count);
  double plane_sq = 0.0;
  for (Eigen::Index k = 0; k < count; ++k) {
    const Vec3 q = model.frame.to_local(points[static_cast<std::size_t>(k)]);
    a.row(k) << 1.0, q.x(), q.y(), q.x() * q.x(), q.x() * q.y(), q.y() * q.y();
    h[k] = q.z();
    plane_sq += q.z() * q.z();
  }
  const double plane_rms = std::sqrt(plane_sq / static_cast<double>(count));
  model.rms = plane_rms;
  if (count < 12 || plane_rms <= resolution) return model;
  const Eigen::VectorXd q = a.colPivHouseholderQr().solve(h);
  const double quad_rms = std::sqrt((a * q - h).squaredNorm() / static_cast<double>(count));
  if (quad_rms * 2.0 <= plane_rms) {
    model.curved = true;
    for (int i = 0; i < 6; ++i) model.q[static_cast<std::size_t>(i)] = q[i];
    model.rms = quad_rms;
  }
  return model;
}

}  // namespace palpa::anatomy
