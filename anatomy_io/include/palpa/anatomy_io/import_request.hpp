#pragma once
// One anatomy import as palpa-cli import and the instructor window's File > Import anatomy
// ask for it (docs/anatomy-import.md): the files, the label table or the tissue's modulus,
// the options; read, fitted, and made into a validated case with its provenance.
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "palpa/anatomy/import.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::anatomy_io {

enum class InputKind { LabelVolume, Mesh, Unknown };

/// By the file's extension (case-insensitive): .nii, .nii.gz, .nrrd, .nhdr, .mhd, .mha, .vti
/// are label volumes; .stl, .obj, .ply meshes.
InputKind input_kind(const std::filesystem::path& path);

struct ImportRequest {
  std::filesystem::path input;          ///< the label volume, the skin mesh or the closed mesh
  std::string labels;                   ///< a label volume's table: "victre", "generic" or a .json file
  /// A label volume's table held in memory (e.g. mapped by hand in the instructor window):
  /// used instead of `labels` when set, checked as a table file would be (a modulus > 0 Pa
  /// for tissue, skin and lesion; names of at most kMaxLabelNameLength characters).
  std::optional<anatomy::LabelTable> table;
  std::filesystem::path support;        ///< the support mesh (with a skin mesh)
  std::optional<std::array<double, 4>> support_plane;  ///< nx, ny, nz, d (d in the mesh's units)
  double modulus = 0.0;                 ///< Pa: a mesh's tissue
  double metres_per_unit = 1e-3;        ///< a mesh's unit (3D Slicer writes mm)
  int rows = 0, cols = 0;               ///< 0: chosen by the fit
  std::string title;                    ///< empty: "Imported from NAME"
  anatomy::ExamRegion region = anatomy::ExamRegion::FreeSurface;
  std::string command;                  ///< the options as given, for the provenance
  std::string tool = "palpa-cli import";  ///< what asked, for the provenance
};

struct ImportedCase {
  anatomy::ImportResult result;
  io::CaseFile file;
  double read_seconds = 0.0;  ///< reading and hashing the input files
};

/// Reads the inputs, imports them and builds the case. Throws anatomy::ImportError with one
/// line naming the file or the option at fault.
ImportedCase import_anatomy(const ImportRequest& request);

/// The label table `labels` names: a built-in one, or a .json file read with its size checked.
anatomy::LabelTable load_label_table(const std::string& labels);

/// Lower-case hex SHA-256 of the file's bytes, read in chunks (a volume may be large).
std::string file_sha256(const std::filesystem::path& path);

}  // namespace palpa::anatomy_io
