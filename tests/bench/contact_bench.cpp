// Cost of one haptic query on the default case: foot point (cold, warm, the paper's
// bisection) and the whole contact (foot point + penetration + force).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "palpa/deform/deformed_body.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"

namespace {

using palpa::Vec3;

const palpa::scene::Scene& default_scene() {
  static const auto scene =
      palpa::scene::Scene::build(palpa::io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"), "default.json");
  return scene;
}

// A palpation-like path: small circles drifting over the breast, pressing 5-20 mm in.
std::vector<Vec3> palpation_path(std::size_t n) {
  std::vector<Vec3> path;
  const auto& body = default_scene().body(0).body;
  std::vector<double> top(3);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * 1e-3;  // 1 kHz
    const double u = 0.5 + 0.3 * std::sin(0.2 * t) + 0.02 * std::cos(6.0 * t);
    const double v = 0.5 + 0.3 * std::cos(0.13 * t) + 0.02 * std::sin(6.0 * t);
    body.top().evaluate(u, v, top);
    const double press = 0.005 + 0.0075 * (1.0 + std::sin(1.7 * t));
    path.emplace_back(top[0], top[1], top[2] - press);
  }
  return path;
}

void BM_FootPointWarm(benchmark::State& state) {
  const auto& sb = default_scene().body(0);
  const auto path = palpation_path(4096);
  double u = 0.5;
  double v = 0.5;
  std::size_t k = 0;
  for (auto _ : state) {
    const auto f = sb.search.closest_from(sb.body.skeleton(), path[k++ & 4095], u, v);
    u = f.u;
    v = f.v;
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_FootPointWarm);

void BM_FootPointCold(benchmark::State& state) {
  const auto& sb = default_scene().body(0);
  const auto path = palpation_path(4096);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(sb.search.closest(sb.body.skeleton(), path[(k += 97) & 4095]));
}
BENCHMARK(BM_FootPointCold);

void BM_FootPointBisect(benchmark::State& state) {
  const auto& sb = default_scene().body(0);
  const auto path = palpation_path(4096);
  const int levels = static_cast<int>(state.range(0));
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(palpa::contact::bisect_foot_point(sb.body.skeleton(), path[k++ & 4095], levels));
}
BENCHMARK(BM_FootPointBisect)->Arg(10)->Arg(20);

void BM_ProbeWarm(benchmark::State& state) {
  const auto& scene = default_scene();
  auto probe_state = scene.make_state();
  palpa::scene::ProbeOptions options;
  options.force.shear = state.range(0) != 0;
  const auto path = palpation_path(4096);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(scene.probe(path[k++ & 4095], probe_state, options));
  state.SetLabel(options.force.shear ? "foot point + depth + force (shear on)" : "shear off");
}
BENCHMARK(BM_ProbeWarm)->Arg(1)->Arg(0);

// The same path on the default case pressed by the rounded finger (contact radius, the
// finger's force and its reading of the tumour's contrast), shear on as the engine asks.
void BM_ProbeWarmFinger(benchmark::State& state) {
  static const auto scene = [] {
    auto file = palpa::io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json");
    file.indenter = palpa::mat::Indenter::Finger;
    return palpa::scene::Scene::build(file, "default.json");
  }();
  auto probe_state = scene.make_state();
  const auto path = palpation_path(4096);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(scene.probe(path[k++ & 4095], probe_state, {}));
  state.SetLabel("rounded finger, tumour in Pa");
}
BENCHMARK(BM_ProbeWarmFinger);

// One haptic tick with dynamics: probe (foot point, depth, force) on the rest body, press
// the drawn body onto the probe, advance its springs by 1 ms. Arg: grid points per side
// of a breast-like dome (0: the default case itself, 9 x 11).
void BM_HapticTickWithDynamics(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  palpa::io::CaseFile file = palpa::io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json");
  if (n > 0) {
    // The default case's body reshaped as an n x n dome of the same tissue (its modulus,
    // the stiffness derived as the case loader derives it).
    auto doc = palpa::io::to_json(file);
    auto& body = doc["bodies"][0];
    const double tissue = body["modulus"][0].get<double>();
    body["rows"] = n;
    body["cols"] = n;
    body["medial"] = nlohmann::json::array();
    body["radius"] = nlohmann::json::array();
    body["modulus"] = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double s = -1.0 + 2.0 * i / (n - 1);
        const double t = -1.0 + 2.0 * j / (n - 1);
        const double f = (1 - s * s) * (1 - t * t);
        body["medial"].push_back({0.07 * s, 0.08 * t, 0.025 * f});
        body["radius"].push_back(0.025 * f);
        body["modulus"].push_back(tissue);
      }
    }
    file = palpa::io::parse_case(doc.dump(), "bench");
  }
  const auto scene = palpa::scene::Scene::build(file, "bench");
  palpa::deform::DeformedBody drawn(scene.body(0).body);
  auto probe_state = scene.make_state();
  palpa::scene::ProbeOptions options;
  options.remember_side = true;
  const auto path = palpation_path(4096);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& q = path[k++ & 4095];
    const auto r = scene.probe(q, probe_state, options);
    if (r.body == 0) {
      drawn.press(r.contact, q);
    } else {
      drawn.release();
    }
    drawn.step(1e-3);
    benchmark::DoNotOptimize(r);
  }
  const auto& sk = scene.body(0).body.skeleton();
  state.counters["control_points"] = sk.rows() * sk.cols();
}
BENCHMARK(BM_HapticTickWithDynamics)->Arg(0)->Arg(16)->Arg(24);

}  // namespace

BENCHMARK_MAIN();
