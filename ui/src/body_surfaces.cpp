#include "palpa/ui/body_surfaces.hpp"

#include <algorithm>

#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkProperty.h>

namespace palpa::ui {

BodySurfaces::BodySurfaces(const live::DisplayMeshes& meshes, vtkRenderer* renderer)
    : bodies_(meshes.size()), meshes_(&meshes) {
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    auto& s = layers_[k];
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
    if (k == 0) {
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

const render::Mesh& BodySurfaces::mesh_of(const live::DisplayMeshes& meshes, std::size_t body, std::size_t layer) {
  return layer == 0 ? meshes.top(body) : meshes.bottom(body);
}

bool BodySurfaces::layout_changed(const live::DisplayMeshes& meshes) const {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    for (std::size_t k = 0; k < layers_.size(); ++k) {
      const auto& mesh = mesh_of(meshes, b, k);
      if (mesh.rows != bodies_[b].rows[k] || mesh.cols != bodies_[b].cols[k]) return true;
    }
  }
  return false;
}

// Gives every body its vertex range in each layer, in body order (when a grid changed
// size: rare, a re-tessellation at another density).
void BodySurfaces::lay_out(const live::DisplayMeshes& meshes) {
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    vtkIdType next = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const auto& mesh = mesh_of(meshes, b, k);
      bodies_[b].first[k] = next;
      bodies_[b].count[k] = static_cast<vtkIdType>(mesh.vertex_count());
      bodies_[b].rows[k] = mesh.rows;
      bodies_[b].cols[k] = mesh.cols;
      next += bodies_[b].count[k];
    }
    layers_[k].points->SetNumberOfPoints(next);
    layers_[k].normals->SetNumberOfTuples(next);
  }
  triangles_stale_ = true;
}

void BodySurfaces::copy(const render::Mesh& mesh, std::size_t body, std::size_t layer) {
  auto& s = layers_[layer];
  const vtkIdType first = bodies_[body].first[layer];
  auto* xyz = static_cast<float*>(s.points->GetData()->GetVoidPointer(0));
  std::copy(mesh.positions.begin(), mesh.positions.end(), xyz + 3 * first);
  std::copy(mesh.normals.begin(), mesh.normals.end(), s.normals->GetPointer(0) + 3 * first);
}

// The triangles of the visible bodies, each body's indices moved to its vertex range.
void BodySurfaces::rebuild_triangles() {
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    std::size_t total = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (bodies_[b].visible) total += mesh_of(*meshes_, b, k).triangles.size();
    }
    vtkNew<vtkIdTypeArray> connectivity;
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(total));
    vtkIdType* out = connectivity->GetPointer(0);
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (!bodies_[b].visible) continue;
      const vtkIdType first = bodies_[b].first[k];
      for (const std::uint32_t v : mesh_of(*meshes_, b, k).triangles) *out++ = first + static_cast<vtkIdType>(v);
    }
    layers_[k].cells->SetData(3, connectivity);
    layers_[k].data->Modified();
  }
  triangles_stale_ = false;
}

std::size_t BodySurfaces::sync(const live::DisplayMeshes& meshes, bool all) {
  meshes_ = &meshes;
  if (layout_changed(meshes)) {
    lay_out(meshes);
    all = true;
  }
  std::size_t copied = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!all && !meshes.changed(b)) continue;
    for (std::size_t k = 0; k < layers_.size(); ++k) copy(mesh_of(meshes, b, k), b, k);
    ++copied;
  }
  if (triangles_stale_) rebuild_triangles();
  if (copied > 0) {
    for (auto& s : layers_) {
      s.points->Modified();
      s.normals->Modified();
      s.data->Modified();
    }
  }
  return copied;
}

void BodySurfaces::set_visible(std::size_t body, bool visible) {
  if (bodies_[body].visible == visible) return;
  bodies_[body].visible = visible;
  rebuild_triangles();
}

void BodySurfaces::set_opacity(double opacity) {
  for (auto& s : layers_) s.actor->GetProperty()->SetOpacity(opacity);
}

}  // namespace palpa::ui
