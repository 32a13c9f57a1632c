#include "palpa/live/display_meshes.hpp"

#include <algorithm>

namespace palpa::live {

DisplayMeshes::DisplayMeshes(const scene::Scene& scene, const deform::DeformOptions& deform,
                             const render::TessellationOptions& options)
    : options_(options) {
  bodies_.reserve(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) {
    auto net = deform::display_net(scene.body(b).body, deform);
    bodies_.push_back(Body{std::move(net.top), std::move(net.bottom), {}, {}, 0, true, true});
    render::tessellate(bodies_.back().top, options_, false, bodies_.back().top_mesh);
    render::tessellate(bodies_.back().bottom, options_, true, bodies_.back().bottom_mesh);
  }
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
    if (!body.visible || b >= snapshot.bodies.size()) continue;
    const auto& shot = snapshot.bodies[b];
    // ~0 marks a snapshot slot never filled by the haptic thread (SceneSnapshot::sized_for).
    if (shot.version == body.version || shot.version == ~std::uint64_t{0}) continue;
    if (shot.top.size() != body.top.control().size() || shot.bottom.size() != body.bottom.control().size()) continue;
    copy_control(shot.top, body.top);
    copy_control(shot.bottom, body.bottom);
    render::tessellate(body.top, options_, false, body.top_mesh);
    render::tessellate(body.bottom, options_, true, body.bottom_mesh);
    body.version = shot.version;
    body.changed = true;
    ++changed;
  }
  return changed;
}

}  // namespace palpa::live
