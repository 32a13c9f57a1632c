#pragma once
// Reading and writing the import's plain types (palpa/anatomy/*.hpp) from and to the files
// segmentation tools write. VTK is used here, never in core; the types handed back carry no
// VTK. Every refusal is an anatomy::ImportError whose what() is one line,
// "FILE: FIELD-OR-PLACE: what is wrong", and sizes are checked from the header before
// anything is allocated.
//
// World coordinates are RAS in metres (palpa/anatomy/label_volume.hpp). Per format:
// - NIfTI-1 (.nii, .nii.gz): RAS by the standard; the sform when sform_code > 0, else the
//   qform (quaternion, qfac = pixdim[0]), else pixdim alone; xyzt_units (unknown = mm).
// - NRRD (.nrrd, .nhdr with a detached data file; raw or gzip): `space` RAS, LPS or LAS
//   (long names too; 3D-right-handed, or `space dimension` without `space`, is taken as RAS),
//   `space directions`, `space origin`;
//   without `space`, `spacings` on the axes; millimetres unless `space units` says otherwise.
// - MetaImage (.mha, .mhd; raw or zlib): ITK's LPS world: TransformMatrix (each three numbers
//   the world direction of one index axis), Offset, ElementSpacing in mm; x and y negated.
// - VTK XML image data (.vti): Origin, Spacing and Direction, taken as RAS in millimetres.
// Meshes (STL, OBJ, PLY) carry no units: coordinates are multiplied by metres_per_unit.
#include <cstdint>
#include <filesystem>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"

namespace palpa::anatomy_io {

/// The largest file read (volume, mesh or detached data): 2 GiB.
inline constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 31;

/// Reads a label volume: NIfTI (.nii, .nii.gz), NRRD (.nrrd, .nhdr with detached data; raw
/// and gzip encodings), MetaImage (.mhd/.mha; raw or zlib-compressed), VTK XML image data
/// (.vti). Chosen by extension (case-insensitive). Voxels may be 8, 16 or 32-bit integers,
/// signed or not, with every value in 0..65535, or float/double holding only such whole
/// numbers. Throws anatomy::ImportError.
anatomy::LabelVolume read_label_volume(const std::filesystem::path& path);

/// Reads a triangle surface: STL (ASCII and binary), OBJ, PLY; polygons triangulated,
/// coincident points merged, coordinates times metres_per_unit (3D Slicer writes mm).
/// Throws anatomy::ImportError.
anatomy::TriangleMesh read_mesh(const std::filesystem::path& path, double metres_per_unit = 1e-3);

/// Writes a label volume by extension, in the formats read_label_volume reads, with its
/// direction and origin, so that reading it back gives the same world placement: .nii and
/// .nii.gz (sform and qform; NIfTI stores float32), .nrrd (gzip, attached), .nhdr (raw
/// data in NAME.raw beside it), .mha (zlib, attached), .mhd (raw data in NAME.raw), .vti.
/// Lengths are written in millimetres. Throws anatomy::ImportError when it cannot.
void write_label_volume(const std::filesystem::path& path, const anatomy::LabelVolume& volume);

/// Writes a triangle mesh by extension: .stl (binary, or ASCII when ascii_stl), .obj, .ply
/// (binary); coordinates divided by metres_per_unit. Throws anatomy::ImportError.
void write_mesh(const std::filesystem::path& path, const anatomy::TriangleMesh& mesh, double metres_per_unit = 1e-3,
                bool ascii_stl = false);

}  // namespace palpa::anatomy_io
