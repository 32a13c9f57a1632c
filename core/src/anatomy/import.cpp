// The three imports (docs/anatomy-import.md): surfaces, fit, tissue, tumours.
#include "palpa/anatomy/import.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "column_tissue.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"

namespace palpa::anatomy {

namespace {

constexpr double kPoisson = 0.49;  // as a case's default: soft tissue is nearly incompressible
constexpr double kSmallestLesion = 1e-3;  // m of radius: smaller is a calcification or noise, not a palpable mass

FittedBody fit(const SurfacePair& pair, const ImportOptions& options) {
  if (options.rows > 0 && options.cols > 0) return fit_body(pair, options.rows, options.cols, options.body_id);
  return fit_body_auto(pair, options.body_id);
}

double grid_spacing(const FittedBody& body) {
  return std::max(body.s_sites[1] - body.s_sites[0], body.t_sites[1] - body.t_sites[0]);
}

// Keeps the lesions the grid resolves: a radius of at least a quarter of its spacing (the
// tissue's modulus around a tumour is read at the skeleton point nearest its centre, and a
// smaller tumour falls between points), of a voxel and of kSmallestLesion.
void keep_resolved(ImportResult& result, double voxel) {
  const double spacing = grid_spacing(result.body);
  const double smallest = std::max({0.25 * spacing, voxel, kSmallestLesion});
  for (Lesion& lesion : result.lesions) {
    if (lesion.radius < smallest) {
      lesion.skipped = fmt::format("{:.1f} mm in radius, below the {:.1f} mm the {:.1f} mm grid resolves",
                                   lesion.radius * 1e3, smallest * 1e3, spacing * 1e3);
      continue;
    }
    lesion.kept = true;
    mat::Tumour tumour;
    tumour.body = result.body.grid.id;
    tumour.center = to_array(lesion.centre);
    tumour.radius = lesion.radius;
    tumour.modulus = lesion.modulus;
    tumour.stiffening = lesion.stiffening;
    result.tumours.push_back(tumour);
  }
}

void uniform_tissue(FittedBody& body, double modulus) {
  if (!(modulus > 0.0 && modulus <= 1e9)) throw ImportError(fmt::format("--modulus: {:g} Pa must be in (0, 1e9]", modulus));
  body.grid.modulus.assign(body.grid.point_count(), modulus);
  body.grid.poisson = kPoisson;
  body.grid.force_model = mat::ForceModel::Calibrated;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A mesh import's body: fitted to its surfaces, of one tissue.
ImportResult uniform_body(SurfacePair surfaces, double modulus, const ImportOptions& options,
                          std::chrono::steady_clock::time_point start) {
  ImportResult result;
  result.surfaces = std::move(surfaces);
  result.body = fit(result.surfaces, options);
  uniform_tissue(result.body, modulus);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace

ImportResult import_label_volume(const LabelVolume& volume, const LabelTable& table, const ImportOptions& options,
                                 const std::string& source) {
  const auto start = std::chrono::steady_clock::now();
  ImportResult result;
  result.surfaces = surfaces_from_volume(volume, table, source);
  result.body = fit(result.surfaces, options);
  result.body.grid.modulus = column_moduli(volume, table, result.surfaces, result.body, kPoisson);
  result.body.grid.poisson = kPoisson;
  result.body.grid.stiffening = dominant_stiffening(volume, table);
  result.body.grid.force_model = mat::ForceModel::Calibrated;
  result.smoothing_passes = smooth_until_fits(result.body.grid);
  result.lesions = find_lesions(volume, table);
  keep_resolved(result, *std::max_element(volume.spacing.begin(), volume.spacing.end()));
  if (table.find(0) == nullptr && std::find(volume.labels.begin(), volume.labels.end(), 0) != volume.labels.end()) {
    result.notes.push_back(fmt::format("label 0 is not in the table \"{}\": taken as outside (the background)",
                                       table.name));
  }
  result.seconds = seconds_since(start);
  return result;
}

ImportResult import_surfaces(const TriangleMesh& skin, const TriangleMesh& support, double modulus,
                             const ImportOptions& options, const std::string& skin_source,
                             const std::string& support_source) {
  const auto start = std::chrono::steady_clock::now();
  return uniform_body(surfaces_from_meshes(skin, support, skin_source, support_source), modulus, options, start);
}

ImportResult import_closed_mesh(const TriangleMesh& mesh, const Vec3& normal, double offset, double modulus,
                                const ImportOptions& options, const std::string& source) {
  const auto start = std::chrono::steady_clock::now();
  return uniform_body(surfaces_from_closed_mesh(mesh, normal, offset, source), modulus, options, start);
}

}  // namespace palpa::anatomy
