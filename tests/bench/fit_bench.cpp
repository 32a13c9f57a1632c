// Fitting cost: a MAT body (skeleton + both contours) for grids of several sizes, and a
// whole scene of 35 bodies / 927 MAT points (the largest scene of the paper's Table 1,
// which took 56 s to preprocess there); and loading a body given in N/m or in Pa (whose
// stiffness is derived from its modulus by contact mechanics).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/fit_residual.hpp"
#include "palpa/mat/mat_body.hpp"

namespace {

using palpa::mat::BodyGrid;
using palpa::mat::MatBody;

// A curved, breast-like body: a dome skeleton with a radius field that is 0 on the boundary.
BodyGrid dome_body(int rows, int cols, double offset_x) {
  BodyGrid g;
  g.id = std::to_string(rows);
  g.id += "x";
  g.id += std::to_string(cols);
  g.rows = rows;
  g.cols = cols;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double s = -1.0 + 2.0 * i / (rows - 1);
      const double t = -1.0 + 2.0 * j / (cols - 1);
      const double f = (1 - s * s) * (1 - t * t);
      g.medial.push_back({offset_x + 0.07 * s, 0.08 * t, 0.025 * f});
      g.radius.push_back(0.025 * f);
      g.stiffness.push_back(120.0 + 180.0 * f);
    }
  }
  return g;
}

void BM_FitBody(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto grid = dome_body(n, n, 0.0);
  double residual = 0.0;
  for (auto _ : state) {
    auto body = MatBody::fit(grid);
    benchmark::DoNotOptimize(body);
  }
  const auto body = MatBody::fit(grid);
  const auto res = palpa::mat::fit_residual(body, grid);
  residual = std::max({res.skeleton[0], res.skeleton[1], res.skeleton[2], res.top, res.bottom});
  state.counters["mat_points"] = n * n;
  state.counters["residual_m"] = residual;
  state.counters["memory_bytes"] = static_cast<double>(body.memory_bytes());
}
BENCHMARK(BM_FitBody)->Arg(7)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

// The A9.4 step alone: a 7-channel skeleton through an n x n grid (parameters, knots,
// two banded factorizations, all solves), comparable with figures other A9.4 implementations report (BENCHMARKS.md).
void BM_InterpolateSkeleton(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto grid = dome_body(n, n, 0.0);
  const auto samples = palpa::mat::skeleton_samples(grid);
  for (auto _ : state) {
    const auto interp = palpa::spline::GridInterpolator::from_grid(samples, n, n, palpa::mat::kSkeletonChannels);
    auto sk = interp.interpolate(samples, palpa::mat::kSkeletonChannels);
    benchmark::DoNotOptimize(sk);
  }
  state.counters["mat_points"] = n * n;
}
BENCHMARK(BM_InterpolateSkeleton)->Arg(7)->Arg(16)->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond);

// 35 bodies, 927 MAT points: 33 bodies of 5 x 5, one of 6 x 7 and one of 6 x 10.
std::vector<BodyGrid> table1_largest_scene() {
  std::vector<BodyGrid> scene;
  for (int b = 0; b < 33; ++b) scene.push_back(dome_body(5, 5, 0.2 * b));
  scene.push_back(dome_body(6, 7, 0.2 * 33));
  scene.push_back(dome_body(6, 10, 0.2 * 34));
  return scene;
}

void BM_FitScene927(benchmark::State& state) {
  const auto scene = table1_largest_scene();
  std::size_t points = 0;
  for (const auto& g : scene) points += g.point_count();
  std::size_t memory = 0;
  for (auto _ : state) {
    memory = 0;
    for (const auto& g : scene) {
      auto body = MatBody::fit(g);
      memory += body.memory_bytes();
      benchmark::DoNotOptimize(body);
    }
  }
  state.counters["bodies"] = static_cast<double>(scene.size());
  state.counters["mat_points"] = static_cast<double>(points);
  state.counters["memory_bytes"] = static_cast<double>(memory);
}
BENCHMARK(BM_FitScene927)->Unit(benchmark::kMillisecond);

// parse_case of one dome body of n x n points, authored in N/m (arg 1 = 0) or in Pa (1).
void BM_ParseCase(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  palpa::io::CaseFile file;
  file.title = "dome";
  file.bodies.push_back(dome_body(n, n, 0.0));
  nlohmann::json doc = palpa::io::to_json(file);
  if (state.range(1) == 1) {
    auto& body = doc["bodies"][0];
    body.erase("stiffness");
    body["modulus"] = std::vector<double>(body["radius"].size(), 5000.0);
  }
  const std::string text = doc.dump();
  for (auto _ : state) benchmark::DoNotOptimize(palpa::io::parse_case(text, "dome.json"));
}
BENCHMARK(BM_ParseCase)->ArgsProduct({{13, 72}, {0, 1}})->ArgNames({"n", "kPa"})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
