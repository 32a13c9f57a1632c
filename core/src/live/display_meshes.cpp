#include "palpa/live/display_meshes.hpp"

#include <algorithm>
#include <cmath>

namespace palpa::live {

DisplayMeshes::DisplayMeshes(const scene::Scene& scene, const deform::DeformOptions& deform,
                             const render::TessellationOptions& options)
    : options_(options) {
  bodies_.reserve(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) {
    auto net = deform::display_net(scene.body(b).body, deform);
    bodies_.push_back(Body{std::move(net.top), std::move(net.bottom), {}, {}, options_, 0, true, true, false});
    tessellate(bodies_.back());
  }
}

void DisplayMeshes::tessellate(Body& body) const {
  render::tessellate(body.top, body.options, false, body.top_mesh);
  render::tessellate(body.bottom, body.options, true, body.bottom_mesh);
}

double DisplayMeshes::deviation(std::size_t body) const {
  const auto& b = bodies_[body];
  return std::max(render::max_parametric_deviation(b.top_mesh, b.top), render::max_parametric_deviation(b.bottom_mesh, b.bottom));
}

bool DisplayMeshes::set_tolerance(std::size_t body, double tolerance) {
  auto& b = bodies_[body];
  render::TessellationOptions o = options_;
  if (tolerance > options_.tolerance && std::isfinite(tolerance)) {
    o.tolerance = tolerance;
    o.uniform_if_cheaper = true;
  }
  if (o == b.options) return false;
  b.options = o;
  b.stale = true;
  return true;
}

namespace {

// Control points of a snapshot into a surface of the same shape (sizes match: the
// snapshot was sized for the same scene).
void copy_control(const std::vector<double>& from, spline::BSplineSurface& to) {
  const int dim = to.dim();
  for (int i = 0; i < to.rows(); ++i) {
    for (int j = 0; j < to.cols(); ++j) {
      const auto point = to.control_point(i, j);
      const auto at = static_cast<std::size_t>((i * to.cols() + j) * dim);
      std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(at), dim, point.begin());
    }
  }
}

}  // namespace

std::size_t DisplayMeshes::update(const engine::SceneSnapshot& snapshot) {
  std::size_t changed = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    auto& body = bodies_[b];
    body.changed = false;
    if (!body.visible) continue;
    if (b < snapshot.bodies.size()) {
      const auto& shot = snapshot.bodies[b];
      // ~0 marks a snapshot slot never filled by the haptic thread (SceneSnapshot::sized_for).
      const bool fresh = shot.version != body.version && shot.version != ~std::uint64_t{0} &&
                         shot.top.size() == body.top.control().size() &&
                         shot.bottom.size() == body.bottom.control().size();
      if (fresh) {
        copy_control(shot.top, body.top);
        copy_control(shot.bottom, body.bottom);
        body.version = shot.version;
        body.stale = true;
      }
    }
    if (!body.stale) continue;
    tessellate(body);
    body.stale = false;
    body.changed = true;
    ++changed;
  }
  return changed;
}

}  // namespace palpa::live
