#include "palpa/ui/body_surfaces.hpp"

#include <algorithm>

#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkProperty.h>

namespace palpa::ui {

BodySurfaces::BodySurfaces(const live::DisplayMeshes& meshes, vtkRenderer* renderer) {
  surfaces_.resize(2 * meshes.size());
  for (std::size_t k = 0; k < surfaces_.size(); ++k) {
    auto& s = surfaces_[k];
    s.data = vtkSmartPointer<vtkPolyData>::New();
    s.points = vtkSmartPointer<vtkPoints>::New();
    s.points->SetDataTypeToFloat();
    s.normals = vtkSmartPointer<vtkFloatArray>::New();
    s.normals->SetNumberOfComponents(3);
    s.normals->SetName("Normals");
    s.cells = vtkSmartPointer<vtkCellArray>::New();
    s.data->SetPoints(s.points);
    s.data->GetPointData()->SetNormals(s.normals);
    s.data->SetPolys(s.cells);
    s.mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    s.mapper->SetInputData(s.data);
    s.mapper->ScalarVisibilityOff();
    s.actor = vtkSmartPointer<vtkActor>::New();
    s.actor->SetMapper(s.mapper);
    auto* property = s.actor->GetProperty();
    property->SetInterpolationToPhong();  // smooth shading from the per-vertex normals
    const bool top = k % 2 == 0;
    if (top) {
      property->SetColor(0.93, 0.74, 0.64);  // skin
    } else {
      property->SetColor(0.70, 0.52, 0.46);
    }
    // A body is closed (top and bottom meet on the skeleton's boundary) and both contours
    // wind counter-clockwise seen from outside, so a back face is never seen: skipping
    // them cuts a quarter of a frame's CPU with software OpenGL (palpa --bench).
    property->BackfaceCullingOn();
    property->SetSpecular(0.25);
    property->SetSpecularPower(20.0);
    renderer->AddActor(s.actor);
  }
  sync(meshes, true);
}

void BodySurfaces::copy(const render::Mesh& mesh, Surface& s) {
  const auto n = static_cast<vtkIdType>(mesh.vertex_count());
  if (s.points->GetNumberOfPoints() != n) {
    s.points->SetNumberOfPoints(n);
    s.normals->SetNumberOfTuples(n);
  }
  auto* xyz = static_cast<float*>(s.points->GetData()->GetVoidPointer(0));
  std::copy(mesh.positions.begin(), mesh.positions.end(), xyz);
  std::copy(mesh.normals.begin(), mesh.normals.end(), s.normals->GetPointer(0));
  if (mesh.rows != s.rows || mesh.cols != s.cols) {  // the grid changed: new triangles (rare)
    vtkNew<vtkIdTypeArray> connectivity;
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(mesh.triangles.size()));
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
      connectivity->SetValue(static_cast<vtkIdType>(k), static_cast<vtkIdType>(mesh.triangles[k]));
    }
    s.cells->SetData(3, connectivity);
    s.rows = mesh.rows;
    s.cols = mesh.cols;
  }
  s.points->Modified();
  s.normals->Modified();
  s.data->Modified();
}

std::size_t BodySurfaces::sync(const live::DisplayMeshes& meshes, bool all) {
  std::size_t copied = 0;
  for (std::size_t b = 0; b < meshes.size(); ++b) {
    if (!all && !meshes.changed(b)) continue;
    copy(meshes.top(b), surfaces_[2 * b]);
    copy(meshes.bottom(b), surfaces_[2 * b + 1]);
    ++copied;
  }
  return copied;
}

void BodySurfaces::set_visible(std::size_t body, bool visible) {
  surfaces_[2 * body].actor->SetVisibility(visible);
  surfaces_[2 * body + 1].actor->SetVisibility(visible);
}

void BodySurfaces::set_opacity(double opacity) {
  for (auto& s : surfaces_) s.actor->GetProperty()->SetOpacity(opacity);
}

}  // namespace palpa::ui
