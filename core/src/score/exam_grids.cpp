#include "exam_grids.hpp"

#include <numbers>

namespace palpa::score::detail {
namespace {

constexpr double kCellSize = 0.002;  // m: coverage cells on the top contour

// Compactness of the covered patch from its radius of gyration r_g: a disc of area A has
// 2 pi r_g^2 = A. The patch is compact when it fills at least this share of the disc its
// spread implies (not a scatter or a ring) ...
constexpr double kCompactFill = 0.5;
// ... and that disc is at most this share of the exam region (one part of it).
constexpr double kCompactShareOfRegion = 0.5;

bool is_compact(const ExamGrids& exam, const CoveredArea& area, const Vec3& moment) {
  const Vec3 centroid = moment / area.covered;
  double spread = 0.0;
  for (std::size_t b = 0; b < exam.grids.size(); ++b) {
    const auto& cell_area = exam.grids[b].areas();
    const auto& level = exam.coverage[b].level();
    for (std::size_t c = 0; c < cell_area.size(); ++c)
      if (level[c] != 0) spread += cell_area[c] * (exam.grids[b].centers()[c] - centroid).squaredNorm();
  }
  const double rg2 = spread / area.covered;
  const double disc = 2.0 * std::numbers::pi * rg2;
  return area.covered >= kCompactFill * disc && disc <= kCompactShareOfRegion * area.region;
}

}  // namespace

ExamGrids::ExamGrids(const scene::Scene& scene, const Thresholds& th, std::vector<std::string>& notes) {
  grids.reserve(scene.size());  // no reallocation: each Coverage refers to its grid
  for (std::size_t b = 0; b < scene.size(); ++b) {
    std::vector<RegionPart> parts;
    for (const auto& p : th.exam_region)
      if (p.body == scene.body(b).body.id()) parts.push_back(p);
    grids.emplace_back(scene.body(b).body, parts, th.exam_region.empty(), kCellSize);
  }
  for (const auto& p : th.exam_region) {
    bool known = false;
    for (std::size_t b = 0; b < scene.size(); ++b) known = known || p.body == scene.body(b).body.id();
    if (!known) notes.push_back("exam region names an unknown body \"" + p.body + "\": ignored");
  }
  for (const auto& g : grids) {
    coverage.emplace_back(g);
    grid_ptrs.push_back(&g);
  }
}

CoveredArea covered_area(const ExamGrids& exam) {
  CoveredArea out;
  Vec3 moment = Vec3::Zero();
  for (std::size_t b = 0; b < exam.grids.size(); ++b) {
    const auto& area = exam.grids[b].areas();
    const auto& level = exam.coverage[b].level();
    out.region += exam.grids[b].region_area();
    for (std::size_t c = 0; c < area.size(); ++c) {
      if (level[c] == 0) continue;
      out.covered += area[c];
      moment += area[c] * exam.grids[b].centers()[c];
      if (level[c] == 3) out.deep += area[c];
    }
  }
  out.compact = out.covered > 0.0 && is_compact(exam, out, moment);
  return out;
}

std::vector<BodyMap> coverage_maps(const scene::Scene& scene, const ExamGrids& exam) {
  std::vector<BodyMap> maps;
  for (std::size_t b = 0; b < exam.grids.size(); ++b) {
    const ContourGrid& grid = exam.grids[b];
    BodyMap map;
    map.body = scene.body(b).body.id();
    map.rows = grid.rows();
    map.cols = grid.cols();
    map.area = grid.areas();
    map.center.reserve(grid.centers().size());
    for (const auto& c : grid.centers())
      map.center.push_back({static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())});
    map.level = exam.coverage[b].level();
    map.dwell_s = exam.coverage[b].dwell();
    map.peak_force_n = exam.coverage[b].peak_force();
    maps.push_back(std::move(map));
  }
  return maps;
}

}  // namespace palpa::score::detail
