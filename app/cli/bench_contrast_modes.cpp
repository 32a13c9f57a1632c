// palpa-cli bench contrast-modes: how clearly a tumour stands out in the two ways the mouse
// presses. Level mode presses to a share of the thickness and reads the force; force mode
// presses to a force and reads the depth and the apparent firmness (kPa, what the gauge
// shows: live::apparent_firmness). For each case
// (tumours placed with --seed) the reading over the first tumour is compared with the same
// reading 12 mm away, on the rest scene with fresh probes (the settled press, without the
// finger's motion).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench_suites.hpp"
#include "commands.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/data_paths.hpp"
#include "palpa/io/thresholds.hpp"
#include "palpa/live/press_control.hpp"
#include "palpa/render/surface_pick.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/scripted/tumour_placement.hpp"

namespace palpa::cli {
namespace {

constexpr double kAway = 0.012;  // m from the tumour's column to the reference spot

struct Spot {
  double u = 0.0, v = 0.0;
};

struct Row {
  std::string case_name, mode;
  double setting = 0.0;          // share (level) or N (force)
  double over = 0.0, away = 0.0; // the reading: N (level) or kPa (force)
  double depth_over = 0.0, depth_away = 0.0;  // m
  double contrast() const { return away > 0.0 ? over / away - 1.0 : 0.0; }
};

class Probe {
 public:
  explicit Probe(const scene::Scene& s) : scene_(&s), state_(s.make_state()) {}
  double force(const Spot& p, double depth) {
    const auto f = live::surface_frame(scene_->body(0).body, p.u, p.v);
    std::fill(state_.warm.begin(), state_.warm.end(), 0);
    state_.held = -1;
    return scene_->probe(f.top - depth * f.normal, state_, {}).force.total.norm();
  }
  double firmness(const Spot& p, double depth) {  // Pa
    return live::apparent_firmness(*scene_, state_, {}, 0, p.u, p.v, depth);
  }
  // The depth at which the force reaches `newtons` (bisection; the deepest press when never).
  double depth_at(const Spot& p, double newtons) {
    const double thickness = live::surface_frame(scene_->body(0).body, p.u, p.v).thickness;
    double lo = 0.0, hi = live::PressureDial::kMaxShare * thickness;
    if (force(p, hi) < newtons) return hi;
    for (int k = 0; k < 50; ++k) (force(p, 0.5 * (lo + hi)) < newtons ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
  double thickness(const Spot& p) const { return live::surface_frame(scene_->body(0).body, p.u, p.v).thickness; }

 private:
  const scene::Scene* scene_;
  scene::ProbeState state_;
};

Spot spot_under(const scene::Scene& s, double x, double y) {
  const auto& b = s.body(0);
  const auto foot = b.search.closest(b.body.skeleton(), Vec3(x, y, b.bounds.hi.z() + 0.05));
  return {foot.u, foot.v};
}

void bench_case(const std::string& name, std::uint64_t seed, std::vector<Row>& rows) {
  const auto placed = scripted::place_tumours(io::load_case(io::bundled_case_path(name)), seed, name);
  const auto s = scene::Scene::build(placed, name);
  std::vector<io::Problem> problems;
  const auto th = io::thresholds_from_case(io::to_json(placed), problems);
  const auto& t = s.body(0).tumours.at(0);
  // 12 mm from the tumour's column towards the body's middle (never off the rim).
  const auto& box = s.body(0).bounds;
  const double cx = 0.5 * (box.lo.x() + box.hi.x()), cy = 0.5 * (box.lo.y() + box.hi.y());
  const double dx = cx - t.center[0], dy = cy - t.center[1], d = std::max(1e-9, std::hypot(dx, dy));
  const Spot over = spot_under(s, t.center[0], t.center[1]);
  const Spot away = spot_under(s, t.center[0] + kAway * dx / d, t.center[1] + kAway * dy / d);
  Probe p(s);
  const double top = live::deepest_plain_share(s, th, {}, live::force_bound(th));
  for (const int level : {1, 4, 7}) {  // the middle step of light, medium, deep
    const double share = live::PressureDial(th, level, top).share();
    Row r{name, "level", share, p.force(over, share * p.thickness(over)), p.force(away, share * p.thickness(away)),
          share * p.thickness(over), share * p.thickness(away)};
    rows.push_back(r);
  }
  for (const double newtons : {3.0, 6.0, 10.0}) {
    const double d_over = p.depth_at(over, newtons), d_away = p.depth_at(away, newtons);
    rows.push_back({name, "force", newtons, p.firmness(over, d_over) * 1e-3, p.firmness(away, d_away) * 1e-3, d_over,
                    d_away});
  }
}

}  // namespace

int run_bench_contrast_modes(const std::filesystem::path& out_dir, std::uint64_t seed) {
  std::vector<Row> rows;
  try {
    for (const char* name : {"default.json", "ladder-1.json", "ladder-2.json", "ladder-3.json", "ladder-4.json"}) {
      bench_case(name, seed, rows);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kBadInput;
  }
  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir / "contrast-modes.csv");
  csv << "case,mode,setting,reading_over,reading_away,contrast,depth_over_m,depth_away_m\n";
  std::printf("%-14s %-6s %8s %14s %14s %9s %10s %10s\n", "case", "mode", "setting", "over tumour", "12 mm away",
              "contrast", "depth over", "depth away");
  for (const auto& r : rows) {
    const bool level = r.mode == "level";
    const char* unit = level ? "N" : "kPa";
    std::printf("%-14s %-6s %8s %9.3f %-4s %9.3f %-4s %8.1f%% %8.1f mm %7.1f mm\n", r.case_name.c_str(), r.mode.c_str(),
                level ? fmt::format("{:.0f} %", r.setting * 100).c_str() : fmt::format("{:.0f} N", r.setting).c_str(),
                r.over, unit, r.away, unit, r.contrast() * 100.0, r.depth_over * 1e3, r.depth_away * 1e3);
    csv << fmt::format("{},{},{},{},{},{},{},{}\n", r.case_name, r.mode, r.setting, r.over, r.away, r.contrast(),
                       r.depth_over, r.depth_away);
  }
  std::printf("wrote %s\n", (out_dir / "contrast-modes.csv").c_str());
  return kOk;
}

}  // namespace palpa::cli
