#pragma once
// Test helpers for the finite-element reference curves (data/reference): a curve's force at
// a depth, and Palpa's force pressing straight down into the middle of a slab's top.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "palpa/scene/scene.hpp"

namespace palpa::reference_test {

/// The force (N) at `depth` (m) of the curve data/reference/`name`, linearly interpolated
/// between its rows; NaN (and a test failure) when the curve does not reach that deep.
inline double reference_force(const std::string& name, double depth) {
  std::ifstream in(std::string(PALPA_SOURCE_DIR) + "/data/reference/" + name);
  std::string line;
  std::getline(in, line);  // depth_m,force_n
  double d0 = 0.0, f0 = 0.0, d1 = 0.0, f1 = 0.0;
  char comma = 0;
  while (in >> d1 >> comma >> f1) {
    if (d1 >= depth) return f0 + (f1 - f0) * (depth - d0) / (d1 - d0);
    d0 = d1;
    f0 = f1;
  }
  ADD_FAILURE() << name << " does not reach " << depth << " m";
  return std::nan("");
}

/// The rows (depth m, force N) of the curve data/reference/`name` past its 0,0 row.
inline std::vector<std::pair<double, double>> reference_curve(const std::string& name) {
  std::ifstream in(std::string(PALPA_SOURCE_DIR) + "/data/reference/" + name);
  std::string line;
  std::getline(in, line);  // depth_m,force_n
  std::vector<std::pair<double, double>> rows;
  double d = 0.0, f = 0.0;
  char comma = 0;
  while (in >> d >> comma >> f) {
    if (d > 0.0) rows.emplace_back(d, f);
  }
  if (rows.empty()) ADD_FAILURE() << name << ": no rows";
  return rows;
}

/// |F| (N) of a press `depth` into the slab's centre, straight down, as the engine probes it
/// (by default its default options: shear springs requested, followed where the body's law
/// has them).
inline double centre_press(const scene::Scene& scene, double depth, const scene::ProbeOptions& options = {}) {
  std::array<double, 3> top{};
  scene.body(0).body.top().evaluate(0.5, 0.5, top);
  auto state = scene.make_state();
  const auto r = scene.probe(palpa::Vec3(top[0], top[1], top[2] - depth), state, options);
  EXPECT_EQ(r.body, 0);
  return r.force.total.norm();
}

/// The engine's options with tumours in Pa felt in the small-strain limit (no growth of the
/// contrast with the press): what the linear FEM sweeps stand for.
inline scene::ProbeOptions small_strain() {
  scene::ProbeOptions o;
  o.force.contrast.compressed = false;
  return o;
}

}  // namespace palpa::reference_test
