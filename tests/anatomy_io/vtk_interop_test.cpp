// anatomy_io's NIfTI reader against VTK's (vtkNIFTIImageReader), an independent reading of
// the qform/sform conventions: the labelled voxel must land on the same world position.
// VTK's reader reverses the slices when qfac = -1 and adjusts its matrix to match, so its
// voxel index differs while the world position may not.
#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedShortArray.h>

#include "palpa/anatomy_io/anatomy_io.hpp"
#include "support.hpp"

namespace palpa::anatomy_io::test {
namespace {

// Where VTK puts the voxel labelled `label`: M (origin + spacing .* index), in metres, M the
// sform when the file has one, else the qform.
std::array<double, 3> vtk_world_of_label(const fs::path& file, int label) {
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  vtkMatrix4x4* m = reader->GetSFormMatrix() != nullptr ? reader->GetSFormMatrix() : reader->GetQFormMatrix();
  EXPECT_NE(m, nullptr);
  const int* dims = image->GetDimensions();
  std::array<double, 3> world{};
  int found = 0;
  for (int k = 0; k < dims[2]; ++k) {
    for (int j = 0; j < dims[1]; ++j) {
      for (int i = 0; i < dims[0]; ++i) {
        if (image->GetScalarComponentAsDouble(i, j, k, 0) != label) continue;
        double p[3];
        const int index[3] = {i, j, k};
        image->TransformIndexToPhysicalPoint(index, p);
        for (int r = 0; r < 3; ++r) {
          world[static_cast<std::size_t>(r)] =
              (m->GetElement(r, 0) * p[0] + m->GetElement(r, 1) * p[1] + m->GetElement(r, 2) * p[2] + m->GetElement(r, 3)) * 1e-3;
        }
        ++found;
      }
    }
  }
  EXPECT_EQ(found, 1);
  return world;
}

void write_with_vtk(const fs::path& file, const double m[16], bool sform) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 5, 6);
  image->SetSpacing(2, 3, 4);
  vtkNew<vtkUnsignedShortArray> labels;
  labels->SetNumberOfValues(4 * 5 * 6);
  labels->FillValue(0);
  labels->SetValue(1 + 4 * (2 + 5 * 3), 5);
  image->GetPointData()->SetScalars(labels);
  vtkNew<vtkMatrix4x4> matrix;
  matrix->DeepCopy(m);
  vtkNew<vtkNIFTIImageWriter> writer;
  writer->SetInputData(image);
  writer->SetQFormMatrix(matrix);
  if (sform) writer->SetSFormMatrix(matrix);
  writer->SetFileName(file.c_str());
  writer->Write();
  ASSERT_EQ(writer->GetErrorCode(), 0u);
}

void expect_same_world(const fs::path& file) {
  const auto ours = world_of_label(read_label_volume(file), 5);
  const auto theirs = vtk_world_of_label(file, 5);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(ours[r], theirs[r], 1e-9) << file.filename() << " coordinate " << r;
}

TEST(VtkInterop, HandWrittenHeadersPlaceTheVoxelWhereVtkDoes) {
  ScratchDir dir;
  write_bytes(dir / "qfac_minus.nii", nifti_header(-1.0f, 1, 0));  // VTK reverses the slices here
  write_bytes(dir / "qfac_plus.nii", nifti_header(1.0f, 1, 0));
  write_bytes(dir / "sform.nii", nifti_header(-1.0f, 1, 2));
  for (const char* name : {"qfac_minus.nii", "qfac_plus.nii", "sform.nii"}) expect_same_world(dir / name);
}

TEST(VtkInterop, FilesWrittenByVtkPlaceTheVoxelWhereVtkDoes) {
  ScratchDir dir;
  // A quarter turn about z, and the same with z mirrored (determinant -1; VTK 9.1's writer
  // keeps the mirror in the sform only and writes qfac = 1: both readers agree on the file).
  const double proper[16] = {0, -1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 30, 0, 0, 0, 1};
  const double mirrored[16] = {0, -1, 0, 10, 1, 0, 0, 20, 0, 0, -1, 30, 0, 0, 0, 1};
  int n = 0;
  for (const double* m : {proper, mirrored}) {
    for (bool sform : {false, true}) {
      const fs::path file = dir / ("vtk" + std::to_string(n++) + ".nii");
      write_with_vtk(file, m, sform);
      expect_same_world(file);
    }
  }
  // With the sform, the mirror is honoured: voxel (1, 2, 3) at z = 30 - 4 * 3 mm.
  EXPECT_NEAR(world_of_label(read_label_volume(dir / "vtk3.nii"), 5)[2], 0.018, 1e-12);
}

}  // namespace
}  // namespace palpa::anatomy_io::test
