#include "palpa/render/surface_pick.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace palpa::render {

TopContourPicker::TopContourPicker(const scene::Scene& scene, double tolerance) {
  render::TessellationOptions options;
  options.tolerance = tolerance;
  meshes_.resize(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) render::tessellate(scene.body(b).body.top(), options, false, meshes_[b]);
}

namespace {

constexpr double kEdgeSlack = 1e-6;  // of a triangle's barycentric range: far below a pixel

Vec3 vertex(const std::vector<float>& xyz, std::uint32_t index) {
  const std::size_t at = std::size_t{index} * 3;
  return {static_cast<double>(xyz[at]), static_cast<double>(xyz[at + 1]), static_cast<double>(xyz[at + 2])};
}

}  // namespace

std::optional<SurfacePick> TopContourPicker::pick(const Vec3& origin, const Vec3& direction) const {
  const double length = direction.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
  const Vec3 d = direction / length;
  std::optional<SurfacePick> best;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < meshes_.size(); ++b) {
    const auto& mesh = meshes_[b];
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
      const std::uint32_t i0 = mesh.triangles[t], i1 = mesh.triangles[t + 1], i2 = mesh.triangles[t + 2];
      // Moller-Trumbore ray/triangle intersection, both faces.
      const Vec3 p0 = vertex(mesh.positions, i0);
      const Vec3 e1 = vertex(mesh.positions, i1) - p0;
      const Vec3 e2 = vertex(mesh.positions, i2) - p0;
      const Vec3 h = d.cross(e2);
      const double det = e1.dot(h);
      if (std::abs(det) < 1e-18) continue;
      const Vec3 s = origin - p0;
      // Barycentric tests with a little slack: a ray through an edge two triangles share
      // (the pointer on a grid line of the tessellation) is rejected by both strict tests
      // through round-off, and the finger would lift in the middle of the body.
      const double a = s.dot(h) / det;
      if (a < -kEdgeSlack || a > 1.0 + kEdgeSlack) continue;
      const Vec3 q = s.cross(e1);
      const double c = d.dot(q) / det;
      if (c < -kEdgeSlack || a + c > 1.0 + kEdgeSlack) continue;
      const double distance = e2.dot(q) / det;
      if (distance <= 0.0 || distance >= nearest) continue;
      nearest = distance;
      SurfacePick hit;
      hit.body = b;
      hit.distance = distance;
      hit.point = origin + distance * d;
      const Vec3 n = (1.0 - a - c) * vertex(mesh.normals, i0) + a * vertex(mesh.normals, i1) +
                     c * vertex(mesh.normals, i2);
      hit.normal = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3(e1.cross(e2).normalized());
      best = hit;
    }
  }
  return best;
}

}  // namespace palpa::render
