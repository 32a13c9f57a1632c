#include "palpa/anatomy_io/anatomy_io.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common.hpp"
#include "vtk_errors.hpp"

namespace palpa::anatomy_io {
namespace detail {

anatomy::TriangleMesh read_mesh_file(const fs::path& file, double metres_per_unit);
void write_mesh_file(const fs::path& file, const anatomy::TriangleMesh& mesh, double metres_per_unit, bool ascii_stl);

namespace {

// "ERROR: In SOURCE-FILE, line N\nCLASS (ADDRESS): MESSAGE": MESSAGE, on one line.
std::string vtk_message(const char* data) {
  std::string text = data != nullptr ? data : "";
  const std::size_t at = text.find("): ");
  if (at != std::string::npos) text = text.substr(at + 3);
  for (char& c : text) c = c == '\n' || c == '\r' ? ' ' : c;
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "VTK reported an error" : text;
}

class SilentWindow : public vtkOutputWindow {
 public:
  static SilentWindow* New() {
    auto* window = new SilentWindow;
    window->InitializeObjectBase();
    return window;
  }
  void DisplayErrorText(const char* text) override { last_error = vtk_message(text); }
  void DisplayText(const char*) override {}
  std::string last_error;
};

}  // namespace

void ErrorCatcher::Execute(vtkObject*, unsigned long, void* data) {
  failed_ = true;
  message_ = vtk_message(static_cast<const char*>(data));
}

QuietVtk::QuietVtk()
    : previous_(vtkOutputWindow::GetInstance()), window_(SilentWindow::New()),
      log_level_(vtkLogger::GetCurrentVerbosityCutoff()) {
  previous_->Register(nullptr);
  vtkOutputWindow::SetInstance(window_);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

QuietVtk::~QuietVtk() {
  vtkLogger::SetStderrVerbosity(log_level_);
  vtkOutputWindow::SetInstance(previous_);
  previous_->UnRegister(nullptr);
  window_->Delete();
}

std::string QuietVtk::last_error() const { return static_cast<SilentWindow*>(window_)->last_error; }

void check_writable(const fs::path& file, const anatomy::LabelVolume& v) {
  Geometry g;
  for (std::size_t a = 0; a < 3; ++a) g.dims[a] = v.dims[a];
  g.spacing = v.spacing;
  g.origin = v.origin;
  g.direction = v.direction;
  const anatomy::LabelVolume checked = checked_volume(file, g, {"dims", "spacing", "origin", "direction"});
  if (v.labels.size() != checked.voxel_count()) {
    fail(file, "labels", fmt::format("{} labels for {} voxels", v.labels.size(), checked.voxel_count()));
  }
}

}  // namespace detail

anatomy::LabelVolume read_label_volume(const std::filesystem::path& path) {
  const std::string ext = detail::lower_extension(path);
  if (ext == ".nii") return detail::read_nifti(path, false);
  if (ext == ".nii.gz") return detail::read_nifti(path, true);
  if (ext == ".nrrd" || ext == ".nhdr") return detail::read_nrrd(path);
  if (ext == ".mha" || ext == ".mhd") return detail::read_metaimage(path);
  if (ext == ".vti") return detail::read_vti(path);
  detail::fail(path, "extension",
               fmt::format("\"{}\" is not a label volume format (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, .vti)", ext));
}

anatomy::TriangleMesh read_mesh(const std::filesystem::path& path, double metres_per_unit) {
  return detail::read_mesh_file(path, metres_per_unit);
}

void write_label_volume(const std::filesystem::path& path, const anatomy::LabelVolume& volume) {
  const std::string ext = detail::lower_extension(path);
  if (ext == ".nii" || ext == ".nii.gz") return detail::write_nifti(path, volume, ext == ".nii.gz");
  if (ext == ".nrrd" || ext == ".nhdr") return detail::write_nrrd(path, volume, ext == ".nhdr");
  if (ext == ".mha" || ext == ".mhd") return detail::write_metaimage(path, volume, ext == ".mhd");
  if (ext == ".vti") return detail::write_vti(path, volume);
  detail::fail(path, "extension", fmt::format("\"{}\" is not a label volume format", ext));
}

void write_mesh(const std::filesystem::path& path, const anatomy::TriangleMesh& mesh, double metres_per_unit,
                bool ascii_stl) {
  detail::write_mesh_file(path, mesh, metres_per_unit, ascii_stl);
}

}  // namespace palpa::anatomy_io
