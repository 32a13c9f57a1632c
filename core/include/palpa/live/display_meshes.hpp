#pragma once
// The GUI thread's copy of the drawn bodies: contour surfaces rebuilt from the haptic
// thread's SceneSnapshot (never from the engine's own bodies, which that thread is
// changing) and tessellated again only for bodies whose version changed.
#include <cstdint>
#include <vector>

#include "palpa/engine/scene_snapshot.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::live {

class DisplayMeshes {
 public:
  /// Starts with every body at rest, tessellated. The scene must outlive this. `deform`
  /// must be the engine's (its display refinement gives the drawn nets' sizes).
  explicit DisplayMeshes(const scene::Scene& scene, const deform::DeformOptions& deform = engine::EngineOptions{}.deform,
                         const render::TessellationOptions& options = {});

  /// Copies the control points of every visible body whose snapshot version differs from
  /// the last one taken and re-tessellates it (and every visible body whose level of detail
  /// changed); returns how many bodies changed (changed(b)
  /// says which). A body set invisible keeps its old meshes and catches up on the first
  /// update after it is visible again. Allocation-free once the meshes have the capacity
  /// for their grids.
  std::size_t update(const engine::SceneSnapshot& snapshot);

  /// Off-screen culling: the GUI says which bodies its camera can see (all at first).
  void set_visible(std::size_t body, bool visible) { bodies_[body].visible = visible; }
  bool visible(std::size_t body) const { return bodies_[body].visible; }

  /// Level of detail: the body's display tolerance (m; the GUI passes a pixel tolerance at
  /// the body's magnification, render::object_tolerance_from_screen), never finer than the
  /// options'. Looser than the options', the grid may be uniform when that has fewer cells
  /// (TessellationOptions::uniform_if_cheaper). A change re-tessellates the body at the next
  /// update() even without a new snapshot. Returns true when the body's tolerance changed.
  bool set_tolerance(std::size_t body, double tolerance);
  double tolerance(std::size_t body) const { return bodies_[body].options.tolerance; }
  /// The largest distance (m) between the body's meshes and the surfaces they stand for
  /// (render::max_parametric_deviation of top and bottom): samples every triangle, for
  /// tests and benchmarks.
  double deviation(std::size_t body) const;

  std::size_t size() const { return bodies_.size(); }
  const render::Mesh& top(std::size_t body) const { return bodies_[body].top_mesh; }
  const render::Mesh& bottom(std::size_t body) const { return bodies_[body].bottom_mesh; }
  /// The body's meshes changed in the last update().
  bool changed(std::size_t body) const { return bodies_[body].changed; }
  /// The snapshot version the meshes show (0 at rest before any snapshot).
  std::uint64_t version(std::size_t body) const { return bodies_[body].version; }

 private:
  struct Body {
    spline::BSplineSurface top, bottom;
    render::Mesh top_mesh, bottom_mesh;
    render::TessellationOptions options;
    std::uint64_t version = 0;
    bool changed = false;
    bool visible = true;
    bool stale = false;  ///< the meshes predate the control points or the options
  };
  void tessellate(Body& body) const;
  std::vector<Body> bodies_;
  render::TessellationOptions options_;
};

}  // namespace palpa::live
