// VTK XML image data (.vti) through vtkXMLImageDataReader / Writer. The file's Origin,
// Spacing and Direction (VTK 9 reads and writes the Direction attribute) are taken as RAS in
// millimetres, as 3D Slicer and the writer below use them; world = Origin + Direction *
// (Spacing .* index), VTK's convention, which is the label volume's.
#include <fmt/format.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkType.h>
#include <vtkIntArray.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <cstring>

#include "common.hpp"
#include "vtk_errors.hpp"

namespace palpa::anatomy_io::detail {
namespace {

Scalar vtk_scalar(const fs::path& file, int type) {
  switch (type) {
    case VTK_UNSIGNED_CHAR: return Scalar::u8;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR: return Scalar::i8;
    case VTK_UNSIGNED_SHORT: return Scalar::u16;
    case VTK_SHORT: return Scalar::i16;
    case VTK_UNSIGNED_INT: return Scalar::u32;
    case VTK_INT: return Scalar::i32;
    case VTK_FLOAT: return Scalar::f32;
    case VTK_DOUBLE: return Scalar::f64;
    default: break;
  }
  fail(file, "PointData", fmt::format("values of VTK type {} are not a label type", type));
}

void check_reader(const fs::path& file, const ErrorCatcher& errors, const QuietVtk& quiet, const char* place) {
  if (errors.failed()) fail(file, place, errors.message());
  if (!quiet.last_error().empty()) fail(file, place, quiet.last_error());
}

// Header-only: the extent is known before the data is read.
Geometry vti_extent(const fs::path& file, vtkXMLImageDataReader& reader, std::array<int, 6>& extent) {
  vtkInformation* info = reader.GetOutputInformation(0);
  if (info == nullptr || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT())) {
    fail(file, "WholeExtent", "missing: not VTK image data");
  }
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent.data());
  Geometry g;
  for (std::size_t a = 0; a < 3; ++a) {
    g.dims[a] = static_cast<std::int64_t>(extent[2 * a + 1]) - extent[2 * a] + 1;
  }
  return g;
}

}  // namespace

anatomy::LabelVolume read_vti(const fs::path& file) {
  checked_file_size(file);
  QuietVtk quiet;
  vtkNew<vtkXMLImageDataReader> reader;
  vtkNew<ErrorCatcher> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(file.c_str());
  reader->UpdateInformation();
  check_reader(file, *errors, quiet, "header");
  std::array<int, 6> extent{};
  Geometry g = vti_extent(file, *reader, extent);
  g.spacing = {1, 1, 1};  // the dims alone are checked here, before the data is read
  anatomy::LabelVolume checked = checked_volume(file, g, {"WholeExtent", "Spacing", "Origin", "Direction"});
  reader->Update();
  check_reader(file, *errors, quiet, "data");
  vtkImageData* image = reader->GetOutput();
  for (std::size_t a = 0; a < 3; ++a) {
    g.spacing[a] = image->GetSpacing()[a] * 1e-3;
    g.origin[a] = image->GetOrigin()[a] * 1e-3;
    for (std::size_t c = 0; c < 3; ++c) {
      g.direction[3 * a + c] = image->GetDirectionMatrix()->GetElement(static_cast<int>(a), static_cast<int>(c));
    }
  }
  // The volume starts at the extent's first index: move the origin there.
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) g.origin[r] += g.direction[3 * r + c] * g.spacing[c] * extent[2 * c];
  }
  anatomy::LabelVolume volume = checked_volume(file, g, {"WholeExtent", "Spacing", "Origin", "Direction"});
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (scalars == nullptr && image->GetPointData()->GetNumberOfArrays() > 0) scalars = image->GetPointData()->GetArray(0);
  if (scalars == nullptr) fail(file, "PointData", "no voxel values could be read (truncated or damaged data, or cell data only)");
  if (scalars->GetNumberOfComponents() != 1) fail(file, "PointData", "more than one value per voxel: not a label volume");
  if (static_cast<std::size_t>(scalars->GetNumberOfTuples()) != checked.voxel_count()) {
    fail(file, "PointData", fmt::format("{} values for {} voxels (truncated)", scalars->GetNumberOfTuples(), checked.voxel_count()));
  }
  Conversion c;
  c.type = vtk_scalar(file, scalars->GetDataType());
  volume.labels.assign(volume.voxel_count(), 0);
  convert_labels(file, static_cast<const unsigned char*>(scalars->GetVoidPointer(0)), volume.voxel_count(), c, 0, volume);
  return volume;
}

void write_vti(const fs::path& file, const anatomy::LabelVolume& v) {
  check_writable(file, v);
  QuietVtk quiet;
  vtkNew<vtkImageData> image;
  image->SetDimensions(v.dims[0], v.dims[1], v.dims[2]);
  image->SetSpacing(v.spacing[0] * 1e3, v.spacing[1] * 1e3, v.spacing[2] * 1e3);
  image->SetOrigin(v.origin[0] * 1e3, v.origin[1] * 1e3, v.origin[2] * 1e3);
  image->SetDirectionMatrix(v.direction.data());
  vtkNew<vtkIntArray> labels;
  labels->SetName("labels");
  labels->SetNumberOfValues(static_cast<vtkIdType>(v.labels.size()));
  static_assert(sizeof(int) == sizeof(anatomy::Label));
  std::memcpy(labels->GetPointer(0), v.labels.data(), v.labels.size() * sizeof(anatomy::Label));
  image->GetPointData()->SetScalars(labels);
  vtkNew<vtkXMLImageDataWriter> writer;
  vtkNew<ErrorCatcher> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetFileName(file.c_str());
  writer->SetInputData(image);
  if (writer->Write() != 1 || errors->failed()) fail(file, "write", errors->failed() ? errors->message() : "VTK cannot write it");
}

}  // namespace palpa::anatomy_io::detail
