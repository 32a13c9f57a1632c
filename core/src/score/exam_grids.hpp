#pragma once
// The exam region as coverage grids, one per body, and what the exam covered of it
// (docs/scoring.md, "Coverage").
#include <string>
#include <vector>

#include "contour_grid.hpp"
#include "coverage.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"

namespace palpa::score::detail {

/// One ContourGrid and its Coverage per body of the scene, restricted to the exam region.
/// Not copyable: each Coverage refers to its grid.
struct ExamGrids {
  /// Grids of the scene's bodies; a region part naming an unknown body adds a note.
  ExamGrids(const scene::Scene& scene, const Thresholds& thresholds, std::vector<std::string>& notes);
  ExamGrids(const ExamGrids&) = delete;
  ExamGrids& operator=(const ExamGrids&) = delete;

  std::vector<ContourGrid> grids;
  std::vector<Coverage> coverage;
  std::vector<const ContourGrid*> grid_ptrs;  ///< for the search-pattern measures
};

/// Areas of the region and of what was covered (m^2), and whether the covered area is
/// one compact patch.
struct CoveredArea {
  double region = 0.0, covered = 0.0, deep = 0.0;
  bool compact = false;
};

CoveredArea covered_area(const ExamGrids& exam);

/// Per-body maps of the coverage for reports.
std::vector<BodyMap> coverage_maps(const scene::Scene& scene, const ExamGrids& exam);

}  // namespace palpa::score::detail
