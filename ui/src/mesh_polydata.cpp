#include "mesh_polydata.hpp"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

namespace palpa::ui {

vtkSmartPointer<vtkPolyData> mesh_polydata(const render::Mesh& mesh, const std::vector<float>* values, const char* name) {
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  const auto n = static_cast<vtkIdType>(mesh.vertex_count());
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  normals->SetNumberOfTuples(n);
  for (vtkIdType v = 0; v < n; ++v) {
    const auto k = static_cast<std::size_t>(3 * v);
    points->SetPoint(v, mesh.positions[k], mesh.positions[k + 1], mesh.positions[k + 2]);
    normals->SetTuple3(v, mesh.normals[k], mesh.normals[k + 1], mesh.normals[k + 2]);
  }
  vtkNew<vtkCellArray> cells;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const vtkIdType ids[3] = {mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]};
    cells->InsertNextCell(3, ids);
  }
  data->SetPoints(points);
  data->GetPointData()->SetNormals(normals);
  data->SetPolys(cells);
  if (values) {
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName(name);
    scalars->SetNumberOfTuples(n);
    for (vtkIdType v = 0; v < n; ++v) scalars->SetValue(v, (*values)[static_cast<std::size_t>(v)]);
    data->GetPointData()->SetScalars(scalars);
  }
  return data;
}

}  // namespace palpa::ui
