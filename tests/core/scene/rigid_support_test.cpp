// Bodies on a rigid support and the contact proxy, on random device paths over every
// bundled case: a finger that slides in from beside the rim, comes from below, jumps or
// is switched on inside must feel the same force a fresh press from above gives there,
// never a push into the support, never a NaN, a force continuous in time, and (on a free
// body) the side it came from.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "palpa/contact/contact.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa {
namespace {


struct NamedScene {
  std::string name;
  scene::Scene scene;
};

const std::vector<NamedScene>& bundled_scenes() {
  static const std::vector<NamedScene> scenes = [] {
    std::vector<NamedScene> out;
    for (const auto& entry : std::filesystem::directory_iterator(PALPA_SOURCE_DIR "/data/cases")) {
      if (entry.path().extension() != ".json") continue;
      const auto name = entry.path().filename().string();
      out.push_back({name, scene::Scene::build(io::load_case(entry.path()), name)});
    }
    return out;
  }();
  return scenes;
}

scene::ProbeOptions path_options() {
  scene::ProbeOptions o;
  o.remember_side = true;  // one probe path, as the engine runs it
  return o;
}

Vec3 unit_normal(const contact::Contact& c) {
  const Vec3 n = c.foot.su.cross(c.foot.sv);
  return n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::UnitZ();
}

// The force a fresh press from above gives at q: the top-contour point over q's column,
// then straight down the normal to q (an independent query with no memory).
Vec3 fresh_press(const scene::Scene& s, const Vec3& q) {
  auto state = s.make_state();
  return s.probe(q, state, scene::ProbeOptions{}).force.total;
}

TEST(Support, BundledAnatomyCasesRestOnTheirSupport) {
  for (const char* name : {"default.json", "two-bodies.json"}) {
    const auto file = io::load_case(std::string(PALPA_SOURCE_DIR "/data/cases/") + name);
    for (const auto& b : file.bodies) EXPECT_EQ(b.support, mat::Support::Bottom) << name << " " << b.id;
  }
  const auto flat = io::load_case(PALPA_SOURCE_DIR "/data/cases/flat-5x5.json");
  EXPECT_EQ(flat.bodies.at(0).support, mat::Support::Free);
}

TEST(Support, SupportFieldValidatesAndRoundTrips) {
  const auto file = io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json");
  auto doc = io::to_json(file);
  EXPECT_EQ(doc["bodies"][0]["support"], "bottom");
  doc["bodies"][0]["support"] = "floor";
  try {
    io::parse_case(doc.dump(), "bad.json");
    FAIL() << "an unknown support was accepted";
  } catch (const io::CaseError& e) {
    EXPECT_EQ(e.problems().at(0).where, "/bodies/0/support");
    EXPECT_NE(std::string(e.what()).find("\"free\" or \"bottom\""), std::string::npos) << e.what();
  }
  doc["bodies"][0]["support"] = "free";
  EXPECT_EQ(io::parse_case(doc.dump(), "free.json").bodies[0].support, mat::Support::Free);
  doc["bodies"][0].erase("support");
  EXPECT_EQ(io::parse_case(doc.dump(), "none.json").bodies[0].support, mat::Support::Free);
}

// The path of the trial that failed: the finger kept a fixed share of the local thickness
// under the top contour while it slid onto the default breast from beside each edge. On
// the support every sample must match a fresh press at the same spot and point out of
// the top surface.
TEST(Support, SlidingOntoTheBreastFromEveryEdgeMatchesAFreshPress) {
  const auto& s = bundled_scenes();
  const auto it = std::find_if(s.begin(), s.end(), [](const NamedScene& n) { return n.name == "default.json"; });
  ASSERT_NE(it, s.end());
  const auto& sc = it->scene;
  const auto& body = sc.body(0);
  for (const double share : {0.10, 0.35, 0.65}) {
    for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0)}) {
      auto state = sc.make_state();
      int in_contact = 0;
      // From 20 mm beside the rim to the centre, 0.05 mm per tick: the finger's depth is
      // the share of the thickness under the skeleton point beneath it.
      const double half = std::abs(dir.x()) > 0 ? 0.07 : 0.08;
      for (double r = half + 0.02; r >= 0.0; r -= 5e-5) {
        const Vec3 plan = -r * dir;
        const auto foot = body.search.closest(body.body.skeleton(), Vec3(plan.x(), plan.y(), 0.03));
        const auto c = contact::make_contact(body.body, foot, foot.point);
        const Vec3 n = unit_normal(c);
        Vec3 q = foot.point + (c.radius - share * 2.0 * c.radius) * n;
        if (r > half) q = Vec3(plan.x(), plan.y(), foot.point.z() - 0.014);  // beside the rim, 14 mm low
        const auto got = sc.probe(q, state, path_options());
        const Vec3 fresh = fresh_press(sc, q);
        ASSERT_TRUE(got.force.total.allFinite());
        if (got.body < 0) continue;
        ++in_contact;
        EXPECT_LE((got.force.total - fresh).norm(), 1e-9 + 1e-9 * fresh.norm()) << "share " << share << " r " << r;
        EXPECT_GE(got.force.total.dot(unit_normal(got.contact)), -1e-9) << "pushes into the chest wall at r " << r;
        EXPECT_LE(got.contact.depth, 2.0 * got.contact.radius + 1e-12);
        EXPECT_GE(got.contact.depth, 0.0);
      }
      EXPECT_GT(in_contact, 1000);
    }
  }
}

TEST(Support, APressToTheChestWallMeetsAStiffWallNeverZero) {
  const auto& sc = std::find_if(bundled_scenes().begin(), bundled_scenes().end(), [](const NamedScene& n) {
                     return n.name == "default.json";
                   })->scene;
  const auto& body = sc.body(0);
  const auto foot = body.search.closest(body.body.skeleton(), Vec3(0.0, 0.0, 0.05));
  const auto top = contact::make_contact(body.body, foot, foot.point);
  const Vec3 n = unit_normal(top);
  const double thickness = 2.0 * top.radius;
  auto state = sc.make_state();
  double last = 0.0;
  const contact::ForceOptions defaults;
  for (double d = 0.0; d <= thickness + 0.01; d += 1e-4) {
    const auto r = sc.probe(foot.point + (top.radius - d) * n, state, path_options());
    ASSERT_EQ(r.body, 0) << "lost contact at depth " << d;
    const double f = r.force.total.dot(n);
    EXPECT_GE(f, last - 1e-9) << "the force fell at depth " << d;  // grows into the support
    if (d > thickness + 1e-3) {
      // Past the bottom contour the support's spring adds on top of the fully pressed tissue.
      EXPECT_NEAR(r.contact.support_depth, d - thickness, 1e-9);
      EXPECT_GT(r.force.support.norm(), 0.9 * defaults.support_stiffness * (d - thickness));
    }
    last = f;
  }
  EXPECT_NEAR(last, defaults.max_force, 1e-9);  // 10 mm into the wall: the cap
}

// Random device paths: drifts between waypoints chosen in, along, under, through and
// around the bodies, with tremor, occasional teleports, and paths that start inside.
struct PathStats {
  long samples = 0;
  long contacts = 0;
  long checked_steps = 0;
  double largest_jump = 0.0;  // N per tick, outside first touches and the wall
  Vec3 largest_at = Vec3::Zero();
  double largest_share = 0.0;  // depth / thickness there
};

constexpr double kForceLipschitz = 1e4;  // N/m: 10 N/mm, 2 N per 0.2 mm tick

void check_random_paths(const NamedScene& ns, int paths, int ticks, std::uint64_t seed, PathStats& stats) {
  const auto& sc = ns.scene;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vec3 lo = sc.body(0).bounds.lo, hi = sc.body(0).bounds.hi;
  for (std::size_t b = 1; b < sc.size(); ++b) {
    lo = lo.cwiseMin(sc.body(b).bounds.lo);
    hi = hi.cwiseMax(sc.body(b).bounds.hi);
  }
  const Vec3 pad = 0.2 * (hi - lo);
  const auto random_point = [&] {
    Vec3 x;
    for (int k = 0; k < 3; ++k) x[k] = lo[k] - pad[k] + unit(rng) * (hi[k] - lo[k] + 2.0 * pad[k]);
    return x;
  };
  const contact::ForceOptions force;
  // Per tick the probe moves at most kStep. Outside the support's wall the force's
  // Lipschitz constant is at most the documented kForceLipschitz (docs/model.md): the
  // tissue (<= 300 N/m here) and a tumour (1500 N/m) along the press, four shear springs,
  // and sideways the tumour's lateral fall-off over a pad radius (up to 1.5 x 30 N / 7.5 mm).
  constexpr double kStep = 2e-4;  // m per tick (0.2 m/s at 1 kHz: a fast hand)
  const double bound = kForceLipschitz * kStep + 1e-9;
  for (int p = 0; p < paths; ++p) {
    auto state = sc.make_state();
    Vec3 q = random_point();
    Vec3 goal = random_point();
    bool have_last = false;
    Vec3 last_force = Vec3::Zero();
    bool last_in_support = false;
    int last_body = -1;
    int entry_side = 0;
    for (int t = 0; t < ticks; ++t) {
      bool jumped = false;
      if (unit(rng) < 0.002) {  // a teleport (a device re-homed, a replay seek)
        q = random_point();
        jumped = true;
      } else {
        if ((goal - q).norm() < kStep || unit(rng) < 0.004) goal = random_point();
        Vec3 step = goal - q;
        step = step.normalized() * std::min(step.norm(), 0.8 * kStep);
        for (int k = 0; k < 3; ++k) step[k] += (unit(rng) - 0.5) * 0.2 * kStep / std::sqrt(3.0);  // tremor
        q += step;
      }
      const Vec3 before = q;
      const auto r = sc.probe(q, state, path_options());
      ++stats.samples;
      ASSERT_TRUE(r.force.total.allFinite()) << ns.name << " path " << p << " tick " << t;
      ASSERT_LE(r.force.total.norm(), force.max_force + 1e-9);
      const bool in_support = r.body >= 0 && r.contact.support_depth > 0.0;
      if (r.body >= 0) {
        ++stats.contacts;
        const auto& body = sc.body(static_cast<std::size_t>(r.body)).body;
        if (body.anchored()) {
          ASSERT_GE(r.force.total.dot(unit_normal(r.contact)), -1e-9) << ns.name << ": pushed into the support";
          ASSERT_GE(r.contact.depth, 0.0);
          ASSERT_LE(r.contact.depth, 2.0 * r.contact.radius + 1e-12) << ns.name;
          ASSERT_EQ(r.contact.side, 1);
        } else if (last_body != r.body || jumped) {
          entry_side = r.contact.side;  // first touch: the side of the skeleton it came in on
        } else {
          ASSERT_EQ(r.contact.side, entry_side) << ns.name << ": the contact flipped sides inside the body";
        }
      }
      // Continuity: a bounded change per tick, except at a first contact, in the support's
      // stiff wall, after a teleport, or when the proxy hands over to another body. Under the
      // skeleton of a body on a support the press is read along its column (docs/model.md),
      // so this holds deep under the imported breast's tight apex too.
      if (have_last && !jumped && r.body >= 0 && r.body == last_body && !in_support && !last_in_support) {
        const double jump = (r.force.total - last_force).norm();
        ASSERT_LE(jump, bound) << ns.name << " path " << p << " tick " << t << " at " << before.transpose();
        if (jump > stats.largest_jump) {
          stats.largest_jump = jump;
          stats.largest_at = before;
          stats.largest_share = r.contact.radius > 0.0 ? r.contact.depth / (2.0 * r.contact.radius) : 0.0;
        }
        ++stats.checked_steps;
      }
      have_last = true;
      last_force = r.force.total;
      last_in_support = in_support;
      last_body = r.body;
    }
  }
}

TEST(Support, RandomDevicePathsKeepEveryPropertyOnEveryBundledCase) {
  const bool long_form = std::getenv("PALPA_LONG_TESTS") != nullptr;
#ifdef NDEBUG
  const int paths = long_form ? 100000 : 300;
#else
  const int paths = long_form ? 100000 : 40;
#endif
  for (const auto& ns : bundled_scenes()) {
    PathStats stats;
    // The long form: 10^5 shorter paths per case (300 ticks: every kind of move fits), so
    // the seven cases run in minutes, not hours.
    check_random_paths(ns, paths, long_form ? 300 : 1500, 2026, stats);
    if (HasFatalFailure()) return;
    // The paths do what they are for: they touch the bodies often and are checked a lot.
    EXPECT_GT(stats.contacts, stats.samples / 20) << ns.name;
    std::printf("%s: %ld samples, %ld in contact, %ld steps checked, largest |dF| %.3f N per tick at (%.1f, %.1f, "
                "%.1f) mm, %.0f %% of the thickness\n",
                ns.name.c_str(), stats.samples, stats.contacts, stats.checked_steps, stats.largest_jump,
                1e3 * stats.largest_at.x(), 1e3 * stats.largest_at.y(), 1e3 * stats.largest_at.z(),
                100.0 * stats.largest_share);
    EXPECT_GT(stats.checked_steps, stats.contacts / 8) << ns.name;  // the rest: in a support's wall (up to 3/4 under the domes)
  }
}

// A probe that appears deep inside an anchored body (a device switched on there, a jump)
// is resolved to the top, like a fresh press; and a free body remembers the entry side.
TEST(Support, AProbeSwitchedOnInsideIsMeasuredFromTheTop) {
  const auto& sc = std::find_if(bundled_scenes().begin(), bundled_scenes().end(), [](const NamedScene& n) {
                     return n.name == "default.json";
                   })->scene;
  const auto& body = sc.body(0);
  const auto foot = body.search.closest(body.body.skeleton(), Vec3(0.01, -0.01, 0.05));
  const auto c = contact::make_contact(body.body, foot, foot.point);
  const Vec3 n = unit_normal(c);
  // 5 mm above the bottom contour: the press is the thickness minus 5 mm from the top, as
  // measured along the column under the skeleton (the column's foot lies a little beside
  // this foot point on the sloping breast, where R differs by a fraction of a millimetre).
  auto state = sc.make_state();
  const Vec3 q = foot.point - (c.radius - 0.005) * n;
  const auto r = sc.probe(q, state, path_options());
  ASSERT_EQ(r.body, 0);
  EXPECT_NEAR(r.contact.depth, 2.0 * c.radius - 0.005, 5e-4);
  // The same contact as a press that came down to it from above the skin, tick by tick.
  auto pressed = sc.make_state();
  scene::ProbeResult down;
  for (double h = 0.03; h >= 0.0; h -= 2e-4) down = sc.probe(q + h * body.press_axis.up, pressed, path_options());
  down = sc.probe(q, pressed, path_options());
  EXPECT_NEAR(down.contact.depth, r.contact.depth, 1e-12);
  EXPECT_NEAR((down.force.total - r.force.total).norm(), 0.0, 1e-9);
  EXPECT_GT(r.force.total.dot(n), 0.0);
  EXPECT_NEAR((r.force.total.normalized() - n).norm(), 0.0, 0.3);
}

TEST(Support, AFreeBodyPressedThroughKeepsItsEntrySide) {
  const auto& sc = std::find_if(bundled_scenes().begin(), bundled_scenes().end(), [](const NamedScene& n) {
                     return n.name == "flat-5x5.json";
                   })->scene;
  ASSERT_FALSE(sc.body(0).body.anchored());
  auto state = sc.make_state();
  // From below: the bottom side is touched first and the press keeps pushing down and out.
  for (double z = -0.03; z < 0.0199; z += 1e-4) {
    const auto r = sc.probe(Vec3(0.0, 0.0, z), state, path_options());
    if (r.body < 0) continue;
    EXPECT_EQ(r.contact.side, -1) << "z " << z;
    EXPECT_LE(r.force.total.z(), 0.0) << "z " << z;
  }
}

}  // namespace
}  // namespace palpa
