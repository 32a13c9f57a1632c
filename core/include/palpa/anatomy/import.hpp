#pragma once
// From segmented anatomy to a case (docs/anatomy-import.md): the surfaces, the fitted MAT
// body, the tissue's modulus per skeleton point from each column's layers, the tumours from
// the lesion labels, and the case file with its provenance.
#include <string>
#include <vector>

#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/mat_fit.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/tumour.hpp"

namespace palpa::anatomy {

struct ImportOptions {
  int rows = 0, cols = 0;  ///< the grid; 0: chosen by fit_body_auto
  std::string body_id = "body";
};

/// One connected component of a lesion label (6-connected voxels).
struct Lesion {
  Label label = 0;
  std::string name;           ///< the label table's name for it
  std::size_t voxels = 0;
  Vec3 centre = Vec3::Zero();  ///< m, world: the voxels' centroid
  double radius = 0.0;         ///< m: the sphere of the same volume
  double modulus = 0.0;        ///< Pa
  double stiffening = 0.0;
  bool kept = false;     ///< became a tumour
  std::string skipped;   ///< why not, for people ("3.2 mm across: smaller than ...")
};

struct ImportResult {
  SurfacePair surfaces;
  FittedBody body;             ///< with modulus per point filled in
  std::vector<Lesion> lesions;  ///< every component found, kept or not
  std::vector<mat::Tumour> tumours;
  double seconds = 0.0;        ///< wall time of the import (reading excluded)
  /// 3 x 3 smoothing passes the tissue's modulus needed so that its stiffness does not
  /// overshoot between the skeleton points (0 for uniform tissue).
  int smoothing_passes = 0;
  /// What the import took for granted, for people ("label 0 is not in the table: taken as
  /// outside, the background").
  std::vector<std::string> notes;
};

/// A label volume to a case body: surfaces_from_volume, fit, column moduli, lesions.
ImportResult import_label_volume(const LabelVolume& volume, const LabelTable& table, const ImportOptions& options,
                                 const std::string& source);

/// A skin mesh on a support mesh, uniform tissue of `modulus` Pa.
ImportResult import_surfaces(const TriangleMesh& skin, const TriangleMesh& support, double modulus,
                             const ImportOptions& options, const std::string& skin_source,
                             const std::string& support_source);

/// A closed mesh on the plane normal . x + offset = 0, uniform tissue of `modulus` Pa.
ImportResult import_closed_mesh(const TriangleMesh& mesh, const Vec3& normal, double offset, double modulus,
                                const ImportOptions& options, const std::string& source);

/// The lesion components of a volume, largest first, each measured; none kept yet.
std::vector<Lesion> find_lesions(const LabelVolume& volume, const LabelTable& table);

/// Where the case came from, written as the case's "provenance" (docs/case-format.md).
struct Provenance {
  std::string source;         ///< the input file's name (no folders)
  std::string sha256;         ///< of the input file's bytes
  std::string support_source; ///< the support mesh's name, if any
  std::string support_sha256;
  std::string labels;         ///< the label table: "victre", "generic" or its file's name
  std::string command;        ///< the options as given, e.g. "--grid 33x33 --labels victre"
};

/// How much of the free surface the exam covers (docs/anatomy-import.md, "Exam region").
enum class ExamRegion { FreeSurface, Whole };

/// The case: one anchored body in kPa, its tumours, the exam region, the provenance and
/// the fit error (both in "provenance"). Validated by io::parse_case before it is returned.
io::CaseFile make_case(const ImportResult& result, const Provenance& provenance, const std::string& title,
                       ExamRegion region);

}  // namespace palpa::anatomy
