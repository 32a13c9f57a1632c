#pragma once
// Where a pointer ray meets the bodies' top contours AT REST. Picking the rest surface,
// not the drawn one, keeps a press stable: the drawn surface sinks under the probe, and a
// target taken from it would chase the surface down.
#include <optional>
#include <vector>

#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/vec3.hpp"

namespace palpa::render {


struct SurfacePick {
  std::size_t body = 0;
  Vec3 point = Vec3::Zero();   ///< m, on the top contour's tessellation
  Vec3 normal = Vec3::UnitZ(); ///< unit, outward (interpolated vertex normal)
  double distance = 0.0;       ///< m, along the ray from its origin
};

class TopContourPicker {
 public:
  /// Tessellates every body's rest top contour (tolerance in m).
  explicit TopContourPicker(const scene::Scene& scene, double tolerance = 1e-4);
  /// The nearest hit of the ray origin + s * direction (s > 0) on any top contour, from
  /// either side; nothing when it misses them all. direction need not be unit length.
  std::optional<SurfacePick> pick(const Vec3& origin, const Vec3& direction) const;
  const Mesh& mesh(std::size_t body) const { return meshes_[body]; }

 private:
  std::vector<Mesh> meshes_;
};

}  // namespace palpa::render
