#pragma once
// Marks against tumours over the top contour (docs/scoring.md, "Marks and tumours").
#include <vector>

#include "contour_grid.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"

namespace palpa::score::detail {

/// Where a point (a mark, a tumour centre) lands on the top contour: the body, the foot
/// point's parameters and the top-contour point over it.
struct Landing {
  int body = -1;
  double u = 0.0, v = 0.0;
  Vec3 top = Vec3::Zero();
};

/// The nearest body by the scene's probe query (every body when all are culled).
Landing land_on_scene(const scene::Scene& scene, const Vec3& q, scene::ProbeState& state);
/// On a given body (a tumour on its own body).
Landing land_on_body(const scene::SceneBody& body, int index, const Vec3& q);

/// Marks placed and not removed, in placement order (the session's rule: an Unmark removes
/// the mark with its id).
std::vector<session::Mark> standing(const std::vector<session::Event>& events);

/// Greedy matching by increasing distance, one mark per tumour: fills tumour.found,
/// tumour.mark, tumour.localization_error_mm and mark.tumour, mark.duplicate,
/// mark.nearest_mm. Returns the number of false positives.
int match_marks(const std::vector<Landing>& mark_tops, const std::vector<Landing>& tumour_tops,
                std::vector<MarkResult>& marks, std::vector<TumourResult>& tumours, double hit_margin);

}  // namespace palpa::score::detail
