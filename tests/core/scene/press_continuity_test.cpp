// Force continuity where a device can press: straight presses down every column of every
// bundled body on a support, to 1 mm above its support, and presses 1 mm apart at the same
// height. A haptic device renders a step of a few newtons within a millimetre as a click
// (docs/model.md, "Under the skeleton: the column"); the paper's nearest-skeleton foot point
// gave 10 N steps deep under the imported breast's apex.
//
// The property: a 0.5 mm step (or a 1 mm neighbour) changes |F| by at most 2 N, or, where the
// tissue itself is that steep (strain stiffening near full compression: b = 11 makes the
// tangent modulus grow e^11-fold across the layer), the change is spread over the step as a
// continuous field's is: refined into 16 parts, no part carries more than a quarter of it.
// A jump carries all of it in one part, however fine the refinement.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/live/press_control.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa {
namespace {

constexpr double kStep = 5e-4;        // m: a straight press's step
constexpr double kApart = 1e-3;       // m: neighbouring presses
constexpr double kAllowed = 2.0;      // N per step or per neighbour
constexpr double kAboveSupport = 1e-3;  // m: presses stop this far above the bottom contour
constexpr int kRefine = 16;

struct Figures {
  long steps = 0, neighbours = 0;
  long steep_steps = 0, steep_neighbours = 0;  // over kAllowed, spread as a continuous field's
  double largest_step = 0.0, largest_neighbour = 0.0;
  double largest_step_force = 0.0;  // N: |F| where the largest step ends
};

Vec3 force_at(const scene::Scene& s, const Vec3& q, scene::ProbeState& state) {
  std::fill(state.warm.begin(), state.warm.end(), 0);
  state.held = -1;
  return s.probe(q, state, {}).force.total;
}

// Whether the change of F from a to b is spread over the segment (no sixteenth of it carries
// more than a quarter of the whole change).
bool spread(const scene::Scene& s, const Vec3& a, const Vec3& b, scene::ProbeState& state) {
  const double whole = (force_at(s, b, state) - force_at(s, a, state)).norm();
  Vec3 last = force_at(s, a, state);
  for (int k = 1; k <= kRefine; ++k) {
    const Vec3 f = force_at(s, a + (b - a) * (static_cast<double>(k) / kRefine), state);
    if ((f - last).norm() > 0.25 * whole) return false;
    last = f;
  }
  return true;
}

// The probe positions of the press down the column through the top-contour point at (u, v):
// from 2 mm above the skin in kStep steps while the tissue under the finger keeps at least
// kAboveSupport; empty where the column is thinner than that.
std::vector<Vec3> column_press(const scene::Scene& s, std::size_t b, double u, double v, scene::ProbeState& state) {
  const auto& sb = s.body(b);
  const Vec3 up = sb.press_axis.up;
  const Vec3 top = live::surface_frame(sb.body, u, v).top;
  std::vector<Vec3> path;
  for (double h = 2e-3;; h -= kStep) {
    const Vec3 q = top + h * up;
    std::fill(state.warm.begin(), state.warm.end(), 0);
    state.held = -1;
    const auto r = s.probe(q, state, {});
    if (r.body == static_cast<int>(b) &&
        (r.contact.support_depth > 0.0 || r.contact.depth > 2.0 * r.contact.radius - kAboveSupport)) {
      break;
    }
    path.push_back(q);
    if (h < -0.2) break;  // 20 cm: past any bundled body
  }
  return path;
}

void check_step(const scene::Scene& s, const Vec3& a, const Vec3& b, const Vec3& fa, const Vec3& fb,
                scene::ProbeState& state, long& count, long& steep, double& largest, const std::string& what) {
  const double change = (fb - fa).norm();
  ++count;
  largest = std::max(largest, change);
  if (change <= kAllowed) return;
  ++steep;
  EXPECT_TRUE(spread(s, a, b, state)) << what << ": " << change << " N from (" << a.transpose() * 1e3 << ") to ("
                                      << b.transpose() * 1e3 << ") mm is a jump";
}

void check_body(const std::string& name, const scene::Scene& s, std::size_t b, int grid, Figures& fig) {
  auto state = s.make_state();
  const auto& sb = s.body(b);
  ASSERT_TRUE(sb.press_axis.usable) << name << ": a bundled body on a support is a graph over its press axis";
  // A sideways unit vector across the press axis, for the neighbouring press.
  const Vec3 side = sb.press_axis.up.unitOrthogonal();
  for (int i = 1; i < grid; ++i) {
    for (int j = 1; j < grid; ++j) {
      const double u = static_cast<double>(i) / grid, v = static_cast<double>(j) / grid;
      const auto path = column_press(s, b, u, v, state);
      Vec3 last = Vec3::Zero();
      for (std::size_t k = 0; k < path.size(); ++k) {
        const Vec3 f = force_at(s, path[k], state);
        if (k > 0) {
          const double before = fig.largest_step;
          check_step(s, path[k - 1], path[k], last, f, state, fig.steps, fig.steep_steps, fig.largest_step,
                     name + " press");
          if (fig.largest_step > before) fig.largest_step_force = f.norm();
        }
        const Vec3 beside = path[k] + kApart * side;
        const auto r = (std::fill(state.warm.begin(), state.warm.end(), 0), s.probe(beside, state, {}));
        const bool in_tissue = r.body == static_cast<int>(b) && r.contact.support_depth == 0.0 &&
                               r.contact.depth <= 2.0 * r.contact.radius - kAboveSupport;
        if (in_tissue) check_step(s, path[k], beside, f, r.force.total, state, fig.neighbours, fig.steep_neighbours,
                                  fig.largest_neighbour, name + " neighbour");
        last = f;
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(PressContinuity, StraightPressesAndNeighboursOnEveryBodyOnASupport) {
#ifdef NDEBUG
  const int grid = 24;
#else
  const int grid = 8;
#endif
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(PALPA_SOURCE_DIR "/data/cases")) {
    if (entry.path().extension() != ".json") continue;
    const auto name = entry.path().filename().string();
    const auto s = scene::Scene::build(io::load_case(entry.path()), name);
    Figures fig;
    for (std::size_t b = 0; b < s.size(); ++b) {
      if (!s.body(b).body.anchored()) continue;
      check_body(name, s, b, grid, fig);
      if (HasFailure()) return;
    }
    if (fig.steps == 0) continue;
    ++cases;
    std::printf("%s: %ld steps of 0.5 mm, largest %.2f N (to %.1f N; %ld over 2 N, all spread); %ld neighbours 1 mm "
                "apart, largest %.2f N (%ld over 2 N, all spread)\n",
                name.c_str(), fig.steps, fig.largest_step, fig.largest_step_force, fig.steep_steps, fig.neighbours,
                fig.largest_neighbour, fig.steep_neighbours);
    EXPECT_GT(fig.neighbours, fig.steps / 2) << name;  // the neighbours were mostly in the tissue too
  }
  EXPECT_GE(cases, 5);  // default, ladder-1..4, victre-breast
}

}  // namespace
}  // namespace palpa
