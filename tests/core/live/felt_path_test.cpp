// The finger's path between two frames, felt every millimetre (live/felt_path.hpp): against
// the firmness read directly along the path, and a stroke over the default case's tumour at
// a busy computer's frame rate against the same stroke read densely.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/live/felt_path.hpp"
#include "palpa/live/press_control.hpp"
#include "palpa/live/stroke_trace.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/scripted/tumour_placement.hpp"

namespace palpa::live {
namespace {

constexpr double kSpeed = 0.1;  // m/s: the guide's sliding speed

struct Stroke {
  scene::Scene scene;
  double u = 0.0, v0 = 0.0, v1 = 0.0;  // a stroke at constant u through the tumour's foot
  double share = 0.5;                  // of the thickness, pressed

  ContactEnd at(double s) const {  // s in [0, 1] along the stroke
    const double v = v0 + s * (v1 - v0);
    const auto f = surface_frame(scene.body(0).body, u, v);
    const double depth = share * f.thickness;
    return {s * length / kSpeed, f.top - depth * f.normal, 0, u, v, depth};
  }
  double length = 0.08;  // m of the finger's path, near enough for the time stamps
};

Stroke default_stroke() {
  const std::string name = "default.json";
  const auto placed = scripted::place_tumours(io::load_case(std::string(PALPA_SOURCE_DIR "/data/cases/") + name), 7, name);
  auto s = scene::Scene::build(placed, name);
  const auto& sb = s.body(0);
  const auto& tu = sb.tumours.at(0);
  const auto foot = sb.search.closest(sb.body.skeleton(), Vec3(tu.center[0], tu.center[1], tu.center[2]));
  Stroke stroke{std::move(s), foot.u, std::max(0.0, foot.v - 0.3), std::min(1.0, foot.v + 0.3)};
  double length = 0.0;
  for (int k = 1; k <= 400; ++k) length += (stroke.at(k / 400.0).finger - stroke.at((k - 1) / 400.0).finger).norm();
  stroke.length = length;
  return stroke;
}

TEST(FeltPath, EveryMillimetreBetweenTwoFramesIsFeltAsIfReadThere) {
  const auto stroke = default_stroke();
  auto state = stroke.scene.make_state(), direct = stroke.scene.make_state();
  std::vector<FeltPoint> out;
  const auto a = stroke.at(0.40), b = stroke.at(0.55);
  felt_between(stroke.scene, state, {}, a, b, out);
  const double travel = (b.finger - a.finger).norm();
  ASSERT_EQ(static_cast<int>(out.size()), static_cast<int>(std::ceil(travel / kFeltStep)));
  Vec3 last = a.finger;
  double last_t = a.t;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto& p = out[k];
    EXPECT_LE((p.finger - last).norm(), kFeltStep + 1e-12);
    EXPECT_GT(p.t, last_t);
    // The firmness is what the window would have read with the finger there.
    const double s = static_cast<double>(k + 1) / static_cast<double>(out.size());
    const double u = a.u + s * (b.u - a.u), v = a.v + s * (b.v - a.v), depth = a.depth + s * (b.depth - a.depth);
    EXPECT_DOUBLE_EQ(p.firmness, apparent_firmness(stroke.scene, direct, {}, 0, u, v, depth));
    const auto column = surface_frame(stroke.scene.body(0).body, u, v);
    EXPECT_DOUBLE_EQ(p.thickness, column.thickness);
    EXPECT_LT((p.skin - column.top).norm(), 1e-12);  // where the finger went into the skin
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
    last = p.finger, last_t = p.t;
  }
  EXPECT_EQ(out.back().finger, b.finger);
  EXPECT_EQ(out.back().t, b.t);
}

TEST(FeltPath, OnlyTheNewEndWhenThePathIsNotOneStretchOfOneBody) {
  const auto stroke = default_stroke();
  auto state = stroke.scene.make_state();
  std::vector<FeltPoint> out;
  const auto a = stroke.at(0.4), b = stroke.at(0.6);
  auto off = a;
  off.body = -1, off.depth = 0.0;
  auto wrapped = a;
  wrapped.u = a.u + 0.9;
  auto late = a;
  late.t = b.t + 1.0;
  for (const auto& from : {off, wrapped, late}) {
    felt_between(stroke.scene, state, {}, from, b, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].finger, b.finger);
    EXPECT_GT(out[0].firmness, 0.0);
  }
  felt_between(stroke.scene, state, {}, a, off, out);  // lifted off: nothing felt
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].firmness, 0.0);
}

// The reason for it: a stroke over the tumour at 10 frames a second (10 mm between frames)
// draws the same bump as one read every half millimetre, within 1 mm and 1 % of its
// height; fed only the frames, the top can fall between two of them.
TEST(FeltPath, AtTenFramesASecondTheTraceDrawsTheLumpWhereAndAsHighAsReadDensely) {
  const auto stroke = default_stroke();
  auto state = stroke.scene.make_state();
  const auto peak_of = [&](int frames, bool fill) {
    StrokeTrace trace;
    std::vector<FeltPoint> out;
    ContactEnd from = stroke.at(0.0);
    for (int k = 0; k <= frames; ++k) {
      const auto to = stroke.at(static_cast<double>(k) / frames);
      if (fill) {
        felt_between(stroke.scene, state, {}, from, to, out);
      } else {
        out = {FeltPoint{to.t, to.finger, apparent_firmness(stroke.scene, state, {}, 0, to.u, to.v, to.depth), 0.0}};
      }
      for (const auto& p : out) trace.feed(p.t, p.finger, p.firmness, 1.0);
      from = to;
    }
    const auto& pts = trace.points();
    const auto top = std::max_element(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.firmness < y.firmness; });
    return std::pair{top->firmness, top->along};
  };
  const int busy_frames = static_cast<int>(std::ceil(stroke.length / 0.010));  // 10 frames a second at 10 cm/s
  const auto dense = peak_of(20 * busy_frames, false);                        // 0.5 mm apart
  const auto busy = peak_of(busy_frames, true);
  const auto coarse = peak_of(busy_frames, false);
  std::printf("lump's top: read every 0.5 mm %.0f Pa at %.1f mm; 10 frames/s filled %.0f Pa at %.1f mm; frames only %.0f Pa at %.1f mm\n",
              dense.first, 1e3 * dense.second, busy.first, 1e3 * busy.second, coarse.first, 1e3 * coarse.second);
  EXPECT_NEAR(busy.first, dense.first, 0.01 * dense.first);
  EXPECT_NEAR(busy.second, dense.second, 0.001);
}

}  // namespace
}  // namespace palpa::live
