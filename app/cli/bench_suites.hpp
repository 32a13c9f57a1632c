#pragma once
// Benchmark suites of `palpa-cli bench` that run on a case file. Each writes a CSV and a
// PNG into its output folder, prints a table and returns the process exit code.
#include <cstdint>
#include <filesystem>

namespace palpa::cli {

/// palpa-cli bench tessellation: the display tessellation of the case's first body (top
/// and bottom contours) at tolerances from 1e-2 m down to 1e-6 m, at rest and pressed
/// 10 mm in: segments, triangles, time per body (median), the largest deviation of the
/// mesh from the surface and whether it is within the tolerance. Writes
/// out_dir/tessellation.csv and out_dir/tessellation.png. Returns 0, or 2 for a case
/// that cannot be loaded or fitted (one line per problem on stderr).
int run_bench_tessellation(const std::filesystem::path& out_dir, const std::filesystem::path& case_path);

/// palpa-cli bench contrast-modes: the tumour's contrast in level mode (force at the middle
/// share of light, medium and deep) against force mode (tangent stiffness dF/dd at 3, 6 and
/// 10 N) over the first tumour of default.json and the ladder cases (tumours placed with
/// `seed`) and 12 mm away, with fresh probes of the rest scene. Writes
/// out_dir/contrast-modes.csv and prints the table. Returns 0, or 2 for a case that cannot
/// be loaded.
int run_bench_contrast_modes(const std::filesystem::path& out_dir, std::uint64_t seed);

/// palpa-cli bench import: a cap on a support voxelized at `voxels`^3 (1 mm voxels at 256)
/// with two masses, written as .nii.gz and imported; the same cap's skin and support as two
/// STL surfaces of 2 (mesh_points - 1)^2 triangles each, imported; and the volume's fit on
/// grids from 9 x 11 to 65 x 65. Time, fit error away from the rim and the process's peak
/// resident memory for each. Writes out_dir/import.csv (and the inputs) and prints the table.
int run_bench_import(const std::filesystem::path& out_dir, int voxels, int mesh_points);

}  // namespace palpa::cli
