#pragma once
// The bodies as VTK actors: per body a top and a bottom vtkPolyData whose points, normals
// and triangles are copied in place from core's tessellation (live::DisplayMeshes),
// only for bodies that changed. The pipeline is built once; a frame only overwrites
// arrays and marks them Modified.
#include <vector>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include "palpa/render/tessellation.hpp"
#include "palpa/live/display_meshes.hpp"

namespace palpa::ui {

class BodySurfaces {
 public:
  /// Builds one actor per contour and adds it to the renderer.
  BodySurfaces(const live::DisplayMeshes& meshes, vtkRenderer* renderer);
  /// Copies the meshes of the bodies that changed in the last DisplayMeshes::update
  /// (all of them when `all`); returns how many bodies were copied.
  std::size_t sync(const live::DisplayMeshes& meshes, bool all = false);
  /// Off-screen culling: hides (or shows) both contours of a body.
  void set_visible(std::size_t body, bool visible);
  /// 1: opaque; lower to see the tumours inside.
  void set_opacity(double opacity);
  /// The top contour's data of a body (tests read its points).
  vtkPolyData* top(std::size_t body) const { return surfaces_[2 * body].data; }

 private:
  struct Surface {
    vtkSmartPointer<vtkPolyData> data;
    vtkSmartPointer<vtkPoints> points;
    vtkSmartPointer<vtkFloatArray> normals;
    vtkSmartPointer<vtkCellArray> cells;
    vtkSmartPointer<vtkPolyDataMapper> mapper;
    vtkSmartPointer<vtkActor> actor;
    int rows = -1, cols = -1;  // grid of the triangles in `cells`
  };
  static void copy(const render::Mesh& mesh, Surface& surface);
  std::vector<Surface> surfaces_;  // top, bottom per body
};

}  // namespace palpa::ui
