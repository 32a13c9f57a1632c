#pragma once
// The bodies as VTK actors: every body's top contour in one vtkPolyData and actor, every
// bottom contour in another. A body's points and normals are copied in place from core's
// tessellation (live::DisplayMeshes) into its own range of the shared arrays, only for
// bodies that changed; the triangles list the visible bodies only. Two draw calls a frame
// whatever the number of bodies: under software OpenGL (Mesa llvmpipe) each actor's draw
// costs about 0.1 ms of the render thread, so 70 actors (35 bodies) cost more than their
// triangles (palpa --bench; BENCHMARKS.md, "Graphics frame rate").
#include <array>
#include <cstddef>
#include <vector>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "palpa/live/display_meshes.hpp"
#include "palpa/render/tessellation.hpp"

namespace palpa::ui {

class BodySurfaces {
 public:
  /// Builds the two actors (tops, bottoms) and adds them to the renderer.
  BodySurfaces(const live::DisplayMeshes& meshes, vtkRenderer* renderer);
  /// Copies the meshes of the bodies that changed in the last DisplayMeshes::update
  /// (all of them when `all`); returns how many bodies were copied.
  std::size_t sync(const live::DisplayMeshes& meshes, bool all = false);
  /// Off-screen culling: leaves both contours of a body out of the drawn triangles (or puts
  /// them back).
  void set_visible(std::size_t body, bool visible);
  /// 1: opaque; lower to see the tumours inside.
  void set_opacity(double opacity);
  /// Every body's top contour, in body order (tests read its points).
  vtkPolyData* tops() const { return layers_[0].data; }

 private:
  struct Layer {  // all tops, or all bottoms
    vtkSmartPointer<vtkPolyData> data;
    vtkSmartPointer<vtkPoints> points;
    vtkSmartPointer<vtkFloatArray> normals;
    vtkSmartPointer<vtkCellArray> cells;
    vtkSmartPointer<vtkPolyDataMapper> mapper;
    vtkSmartPointer<vtkActor> actor;
  };
  struct Body {
    std::array<vtkIdType, 2> first{0, 0}, count{0, 0};  // vertex range per layer
    std::array<int, 2> rows{-1, -1}, cols{-1, -1};      // grid of the triangles last laid out
    bool visible = true;
  };
  static const render::Mesh& mesh_of(const live::DisplayMeshes& meshes, std::size_t body, std::size_t layer);
  bool layout_changed(const live::DisplayMeshes& meshes) const;
  void lay_out(const live::DisplayMeshes& meshes);
  void copy(const render::Mesh& mesh, std::size_t body, std::size_t layer);
  void rebuild_triangles();

  std::array<Layer, 2> layers_;
  std::vector<Body> bodies_;
  const live::DisplayMeshes* meshes_ = nullptr;  // for the triangles of set_visible
  bool triangles_stale_ = true;
};

}  // namespace palpa::ui
