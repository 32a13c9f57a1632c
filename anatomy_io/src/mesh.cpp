// Triangle meshes through VTK's readers and writers (STL, OBJ, PLY). The sizes a header
// claims (a binary STL's triangle count, a PLY's element counts) are checked here before
// VTK allocates anything; VTK's output is checked again (indices, finite coordinates) before
// it is triangulated and its coincident points merged.
#include <fmt/format.h>
#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkOBJWriter.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "common.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "text_header.hpp"
#include "vtk_errors.hpp"

namespace palpa::anatomy_io::detail {
namespace {

// Binary when the size is exactly 84 + 50 n for the count n in the header; ASCII when it
// starts with "solid"; anything else is a binary STL whose count disagrees with its size.
void check_stl(const fs::path& file, std::uintmax_t size) {
  std::array<unsigned char, 84> head{};
  std::ifstream in(file, std::ios::binary);
  in.read(reinterpret_cast<char*>(head.data()), 84);
  const auto got = static_cast<std::size_t>(in.gcount());
  std::uint32_t count = 0;
  if (got == 84) std::memcpy(&count, head.data() + 80, 4);
  const bool binary = got == 84 && size == 84 + std::uintmax_t{50} * count;
  const std::string start = lower_trimmed(std::string(reinterpret_cast<const char*>(head.data()), got));
  if (!binary && start.starts_with("solid")) return;  // ASCII: bounded by the file size
  if (got < 84) fail(file, "header", "shorter than a binary STL's 84-byte header");
  if (count > anatomy::kMaxTriangles) {
    fail(file, "triangle count", fmt::format("{} triangles, more than the {} a mesh may have", count, anatomy::kMaxTriangles));
  }
  if (!binary) {
    fail(file, "triangle count",
         fmt::format("the header says {} triangles ({} bytes), the file has {} bytes", count,
                     84 + std::uintmax_t{50} * count, size));
  }
  if (count == 0) fail(file, "triangle count", "no triangles");
}

// A PLY header's element counts, checked against the limits and the file size.
void check_ply(const fs::path& file, std::uintmax_t size) {
  const std::string head = read_head(file, std::min<std::uintmax_t>(size, 65536));
  const std::size_t end = head.find("end_header");
  if (!head.starts_with("ply") || end == std::string::npos) fail(file, "header", "not a PLY header (ply ... end_header)");
  const bool ascii = head.find("format ascii") != std::string::npos;
  for (const std::string& line : split_lines(head.substr(0, end))) {
    std::vector<std::string> words;
    for (std::size_t i = 0, j = 0; i < line.size(); i = j + 1) {
      j = line.find(' ', i);
      if (j == std::string::npos) j = line.size();
      if (j > i) words.push_back(line.substr(i, j - i));
    }
    if (words.size() != 3 || words[0] != "element") continue;
    std::int64_t n = 0;
    if (!parse_int64(words[2], n) || n < 0) fail(file, "element " + words[1], "not a count");
    const std::uintmax_t least = ascii ? 2 : 1;  // bytes per element at the very least
    if (static_cast<std::uintmax_t>(n) > anatomy::kMaxTriangles) {
      fail(file, "element " + words[1], fmt::format("{}, more than the {} read", n, anatomy::kMaxTriangles));
    }
    if (static_cast<std::uintmax_t>(n) * least > size) {
      fail(file, "element " + words[1], fmt::format("{} elements cannot fit in {} bytes (truncated)", n, size));
    }
  }
}

vtkSmartPointer<vtkAlgorithm> mesh_reader(const fs::path& file, const std::string& ext, std::uintmax_t size) {
  if (ext == ".stl") {
    check_stl(file, size);
    auto reader = vtkSmartPointer<vtkSTLReader>::New();
    reader->SetFileName(file.c_str());
    return reader;
  }
  if (ext == ".ply") {
    check_ply(file, size);
    auto reader = vtkSmartPointer<vtkPLYReader>::New();
    reader->SetFileName(file.c_str());
    return reader;
  }
  if (ext == ".obj") {
    auto reader = vtkSmartPointer<vtkOBJReader>::New();
    reader->SetFileName(file.c_str());
    return reader;
  }
  fail(file, "extension", fmt::format("\"{}\" is not a mesh format (.stl, .obj, .ply)", ext));
}

// What VTK read, before any filter touches it: indices in range, coordinates finite.
void check_polydata(const fs::path& file, vtkPolyData* data) {
  if (data == nullptr || data->GetPoints() == nullptr || data->GetNumberOfPoints() == 0) fail(file, "points", "none");
  const vtkIdType points = data->GetNumberOfPoints();
  for (vtkIdType p = 0; p < points; ++p) {
    const double* x = data->GetPoint(p);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
      fail(file, fmt::format("point {}", p), "coordinate is not finite");
    }
  }
  vtkCellArray* polys = data->GetPolys();
  if (polys == nullptr || polys->GetNumberOfCells() == 0) fail(file, "triangles", "none");
  if (static_cast<std::uintmax_t>(polys->GetNumberOfCells()) > anatomy::kMaxTriangles) {
    fail(file, "triangles", fmt::format("{}, more than the {} a mesh may have", polys->GetNumberOfCells(), anatomy::kMaxTriangles));
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; cell < polys->GetNumberOfCells(); ++cell) {
    polys->GetCellAtId(cell, ids);
    for (vtkIdType n = 0; n < ids->GetNumberOfIds(); ++n) {
      if (ids->GetId(n) < 0 || ids->GetId(n) >= points) {
        fail(file, fmt::format("polygon {}", cell), fmt::format("point index {} is out of range (0..{})", ids->GetId(n), points - 1));
      }
    }
  }
}

anatomy::TriangleMesh to_mesh(const fs::path& file, vtkPolyData* clean, double metres_per_unit) {
  anatomy::TriangleMesh mesh;
  mesh.points.resize(static_cast<std::size_t>(clean->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < clean->GetNumberOfPoints(); ++p) {
    const double* x = clean->GetPoint(p);
    mesh.points[static_cast<std::size_t>(p)] = {x[0] * metres_per_unit, x[1] * metres_per_unit, x[2] * metres_per_unit};
  }
  vtkCellArray* polys = clean->GetPolys();
  vtkNew<vtkIdList> ids;
  mesh.triangles.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  for (vtkIdType cell = 0; cell < polys->GetNumberOfCells(); ++cell) {
    polys->GetCellAtId(cell, ids);
    if (ids->GetNumberOfIds() != 3) fail(file, fmt::format("polygon {}", cell), "not a triangle after triangulation");
    mesh.triangles.push_back({static_cast<std::int32_t>(ids->GetId(0)), static_cast<std::int32_t>(ids->GetId(1)),
                              static_cast<std::int32_t>(ids->GetId(2))});
  }
  if (mesh.triangles.empty()) fail(file, "triangles", "none left after removing degenerate ones");
  return mesh;
}

}  // namespace

anatomy::TriangleMesh read_mesh_file(const fs::path& file, double metres_per_unit) {
  if (!std::isfinite(metres_per_unit) || !(metres_per_unit > 0)) {
    fail(file, "metres_per_unit", fmt::format("{} must be finite and positive", metres_per_unit));
  }
  const std::string ext = lower_extension(file);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply") {
    fail(file, "extension", fmt::format("\"{}\" is not a mesh format (.stl, .obj, .ply)", ext));
  }
  const std::uintmax_t size = checked_file_size(file);
  QuietVtk quiet;
  vtkSmartPointer<vtkAlgorithm> reader = mesh_reader(file, ext, size);
  vtkNew<ErrorCatcher> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->Update();
  if (errors->failed()) fail(file, "read", errors->message());
  if (!quiet.last_error().empty()) fail(file, "read", quiet.last_error());
  auto* raw = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  check_polydata(file, raw);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(raw);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  vtkNew<vtkCleanPolyData> clean;  // tolerance 0: only coincident points are merged
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->SetTolerance(0.0);
  clean->PointMergingOn();
  clean->Update();
  return to_mesh(file, clean->GetOutput(), metres_per_unit);
}

void write_mesh_file(const fs::path& file, const anatomy::TriangleMesh& mesh, double metres_per_unit, bool ascii_stl) {
  if (!std::isfinite(metres_per_unit) || !(metres_per_unit > 0)) fail(file, "metres_per_unit", "must be finite and positive");
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : mesh.points) points->InsertNextPoint(p[0] / metres_per_unit, p[1] / metres_per_unit, p[2] / metres_per_unit);
  vtkNew<vtkCellArray> cells;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::int32_t i : tri) {
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.points.size()) fail(file, fmt::format("triangle {}", t), "index out of range");
    }
    const vtkIdType ids[3] = {tri[0], tri[1], tri[2]};
    cells->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetPolys(cells);
  const std::string ext = lower_extension(file);
  QuietVtk quiet;
  vtkNew<ErrorCatcher> errors;
  int written = 0;
  if (ext == ".stl") {
    vtkNew<vtkSTLWriter> writer;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    if (ascii_stl) writer->SetFileTypeToASCII(); else writer->SetFileTypeToBinary();
    writer->SetFileName(file.c_str());
    writer->SetInputData(data);
    written = writer->Write();
  } else if (ext == ".obj") {
    vtkNew<vtkOBJWriter> writer;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileName(file.c_str());
    writer->SetInputData(data);
    written = writer->Write();
  } else if (ext == ".ply") {
    vtkNew<vtkPLYWriter> writer;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileTypeToBinary();
    writer->SetFileName(file.c_str());
    writer->SetInputData(data);
    written = writer->Write();
  } else {
    fail(file, "extension", fmt::format("\"{}\" is not a mesh format (.stl, .obj, .ply)", ext));
  }
  if (written != 1 || errors->failed()) fail(file, "write", errors->failed() ? errors->message() : "VTK cannot write it");
}

}  // namespace palpa::anatomy_io::detail
