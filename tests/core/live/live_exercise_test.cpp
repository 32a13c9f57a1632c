// The live trainee exercise (live::LiveExercise) on the real haptic loop: pressing over
// the tumour pushes back and deforms the drawn body; a mark over the tumour is found by
// the score read back from the session file, a mark far away is a false positive.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <thread>

#include "palpa/live/live_exercise.hpp"

namespace palpa::live {
namespace {

const std::string kDefaultCase = PALPA_SOURCE_DIR "/data/cases/default.json";

class ScratchDir {
 public:
  ScratchDir() {
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() / ("palpa-trainer-" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

LiveOptions options_for(const std::filesystem::path& session) {
  LiveOptions o;
  o.trainee = "t1";
  o.seed = 7;
  o.session_path = session;
  o.realtime.request_fifo = false;  // tests run beside other work: no real-time priority needed
  o.device_settling = 0.01;
  return o;
}

/// Updates until `done` holds or the deadline (generous: a loaded machine) passes.
bool run_until(LiveExercise& live, const std::function<bool()>& done, double seconds = 5.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    live.update();
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

/// The rest top contour straight above a point (a vertical ray from high above).
render::SurfacePick top_above(const LiveExercise& live, const Vec3& point) {
  const auto hit = live.pick(point + Vec3(0, 0, 0.5), Vec3(0, 0, -1));
  EXPECT_TRUE(hit.has_value());
  return hit.value_or(render::SurfacePick{});
}

TEST(TopContourPicker, HitsTheTopContourWhereTheProbeJustTouches) {
  const auto file = io::load_case(kDefaultCase);
  LiveExercise live(file, kDefaultCase, options_for("unused.palpa"));
  const auto& tumour = live.placed_case().tumours.at(0);
  const Vec3 centre(tumour.center[0], tumour.center[1], tumour.center[2]);
  const auto hit = top_above(live, centre);
  EXPECT_NEAR(hit.distance, 0.5 - (hit.point.z() - centre.z()), 1e-9);
  EXPECT_GT(hit.point.z(), centre.z() + tumour.radius);  // the tumour lies under the surface
  EXPECT_GT(hit.normal.z(), 0.5);                        // outward normal of a top contour points up
  // Independent truth: the scene's own probe query finds the picked point on the surface.
  auto state = live.scene().make_state();
  const auto on = live.scene().probe(hit.point, state);
  EXPECT_NEAR(on.contact.depth, 0.0, 2e-4);
  // A ray that passes beside every body hits nothing.
  EXPECT_FALSE(live.pick(Vec3(5, 5, 5), Vec3(0, 0, 1)).has_value());
  EXPECT_FALSE(std::filesystem::exists("unused.palpa"));  // nothing written before start()
}

// The pointer on a grid line of the tessellation: a ray through the edge two triangles
// share must hit one of them (strict barycentric tests rejected both through round-off,
// and a trainee sliding along x = 0 saw the finger lift every few millimetres).
TEST(TopContourPicker, RaysThroughSharedEdgesHit) {
  const auto file = io::load_case(kDefaultCase);
  LiveExercise live(file, kDefaultCase, options_for("unused.palpa"));
  int rays = 0, missed = 0;
  for (int i = -65; i <= 65; i += 5) {
    for (int j = -75; j <= 75; ++j) {
      const Vec3 plan(i * 1e-3, j * 1e-3, 0.0);
      ++rays;
      const auto down = live.pick(plan + Vec3(0, 0, 1.0), Vec3(0, 0, -1));
      if (!down) {
        ++missed;
        continue;
      }
      // The same point seen from the front and above, as the window's camera looks.
      const Vec3 eye = down->point + 0.5 * Vec3(0.0, -0.6, 0.8);
      if (!live.pick(eye, down->point - eye)) ++missed;
    }
  }
  EXPECT_EQ(missed, 0) << "of " << rays << " rays";
}

TEST(LiveExercise, PressingOverTheTumourPushesBackAndDeformsTheDrawnBody) {
  ScratchDir dir;
  const auto file = io::load_case(kDefaultCase);
  LiveExercise live(file, kDefaultCase, options_for(dir / "press.palpa"));
  const auto rest_top = live.meshes().top(0).positions;
  live.start();
  const auto& tumour = live.placed_case().tumours.at(0);
  const auto hit = top_above(live, Vec3(tumour.center[0], tumour.center[1], tumour.center[2]));
  live.set_probe_target(hit.point - 0.008 * hit.normal);  // 8 mm into the tissue
  // The virtual device follows the target smoothly: wait until the finger has arrived.
  ASSERT_TRUE(run_until(live, [&] {
    // About 1 N there (BENCHMARKS.md, "The tumour felt by light and deep presses").
    return live.contact().force > 0.5 && live.contact().depth > 0.0075 && live.meshes().version(0) > 0;
  })) << "force " << live.contact().force << " depth " << live.contact().depth;
  const auto c = live.contact();
  EXPECT_EQ(c.body, 0);
  EXPECT_NEAR(c.depth, 0.008, 5e-4);  // the target's depth below the rest top contour
  EXPECT_GT(c.thickness, 0.0);
  EXPECT_NEAR(c.fraction, c.depth / c.thickness, 1e-12);
  EXPECT_NE(c.level, PressureLevel::None);
  // The drawn top contour moved: some vertex sank by at least a millimetre.
  ASSERT_TRUE(run_until(live, [&] {
    const auto& now = live.meshes().top(0).positions;
    if (now.size() != rest_top.size()) return true;
    float sink = 0.0f;
    for (std::size_t k = 2; k < now.size(); k += 3) sink = std::max(sink, rest_top[k] - now[k]);
    return sink > 1e-3f;
  }));
  // The loop publishes its statistics every 100 ticks.
  EXPECT_TRUE(run_until(live, [&] { return live.loop_stats().ticks() >= 100; }));
  const auto score = live.finish();
  EXPECT_GT(score.peak_force_n, 0.5);  // the press above, recorded
}

TEST(LiveExercise, MarkOverTheTumourIsFoundAndAMarkFarAwayIsAFalsePositive) {
  ScratchDir dir;
  const auto file = io::load_case(kDefaultCase);
  LiveExercise live(file, kDefaultCase, options_for(dir / "marks.palpa"));
  live.start();
  const auto& tumour = live.placed_case().tumours.at(0);
  const Vec3 centre(tumour.center[0], tumour.center[1], tumour.center[2]);
  const auto over = top_above(live, centre);
  live.set_probe_target(over.point - 0.010 * over.normal);  // about 1.4 N over the tumour
  ASSERT_TRUE(run_until(live, [&] { return live.contact().force > 1.0; }));
  const auto hit_mark = live.place_mark();
  EXPECT_EQ(hit_mark.id, 1);
  EXPECT_LT((hit_mark.position - over.point).norm(), 0.011);  // where the finger is, 10 mm in

  // Far away: a corner of the body, 40 mm or more from the tumour's centre.
  const auto& bounds = live.scene().body(0).bounds;
  const Vec3 corner = bounds.lo + 0.2 * (bounds.hi - bounds.lo);
  const auto far = top_above(live, Vec3(corner.x(), corner.y(), centre.z()));
  ASSERT_GT((far.point - centre).norm(), 0.04);
  live.set_probe_target(far.point - 0.002 * far.normal);
  ASSERT_TRUE(run_until(live, [&] {
    const auto& p = live.snapshot().probe;
    return (Vec3(p[0], p[1], p[2]) - far.point).norm() < 0.004;
  }));
  const auto far_mark = live.place_mark();
  // A third mark, removed again: it must not count.
  const auto removed = live.place_mark();
  EXPECT_TRUE(live.remove_mark(removed.id));
  EXPECT_FALSE(live.remove_mark(removed.id));
  EXPECT_EQ(live.marks().size(), 2u);

  const auto score = live.finish();
  EXPECT_THROW(live.finish(), std::logic_error);
  ASSERT_EQ(score.tumours.size(), 1u);
  EXPECT_TRUE(score.tumours[0].found);
  EXPECT_EQ(score.tumours[0].mark, hit_mark.id);
  EXPECT_DOUBLE_EQ(score.sensitivity, 1.0);
  EXPECT_EQ(score.false_positives, 1);
  ASSERT_EQ(score.marks.size(), 2u);
  EXPECT_EQ(score.marks[1].id, far_mark.id);
  EXPECT_EQ(score.marks[1].tumour, -1);
  EXPECT_TRUE(score.complete);
  EXPECT_GT(score.samples, 10u);
}

TEST(LiveExercise, ABadTraineeOrAnExistingSessionFileIsRefused) {
  ScratchDir dir;
  const auto file = io::load_case(kDefaultCase);
  auto o = options_for(dir / "exists.palpa");
  o.trainee = "";
  EXPECT_THROW(LiveExercise(file, kDefaultCase, o), std::invalid_argument);
  o.trainee = "t1";
  { std::ofstream(dir / "exists.palpa") << "x"; }
  LiveExercise live(file, kDefaultCase, o);
  EXPECT_THROW(live.start(), session::SessionError);
  EXPECT_THROW(live.place_mark(), std::logic_error);
}

}  // namespace
}  // namespace palpa::live
