#pragma once
// Internal to ui/: core's display mesh as a VTK polydata (positions, normals, triangles),
// with one named scalar per vertex when given (the instructor's stiffness, the import
// preview's fit error).
#include <vector>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "palpa/render/tessellation.hpp"

namespace palpa::ui {

vtkSmartPointer<vtkPolyData> mesh_polydata(const render::Mesh& mesh, const std::vector<float>* values = nullptr,
                                           const char* name = "");

}  // namespace palpa::ui
