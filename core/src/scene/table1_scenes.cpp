#include "palpa/scene/table1_scenes.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace palpa::scene {

const std::vector<Table1Scene>& table1_scenes() {
  static const std::vector<Table1Scene> scenes{
      {1, 49, {{1, 7, 7}}, 2, 0.4, 980, 993},
      {1, 105, {{1, 7, 15}}, 3, 1.0, 979, 996},
      {4, 213, {{3, 7, 8}, {1, 5, 9}}, 6, 1.8, 990, 993},
      {10, 309, {{7, 5, 6}, {3, 3, 11}}, 9, 2.1, 980, 992},
      {17, 465, {{15, 5, 5}, {1, 6, 8}, {1, 6, 7}}, 25, 3.0, 975, 980},
      {35, 927, {{33, 5, 5}, {1, 6, 7}, {1, 6, 10}}, 56, 4.1, 980, 990},
  };
  return scenes;
}

// Breast-like domes side by side along x, 12 cm apart.
io::CaseFile make_table1_case(const Table1Scene& spec) {
  io::CaseFile file;
  file.title = fmt::format("Table 1 scene, {} bodies", spec.bodies);
  int index = 0;
  for (const auto& [count, rows, cols] : spec.grids) {
    for (int c = 0; c < count; ++c, ++index) {
      mat::BodyGrid g;
      g.id = fmt::format("b{}", index);
      g.rows = rows;
      g.cols = cols;
      for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
          const double s = -1.0 + 2.0 * i / (rows - 1);
          const double t = -1.0 + 2.0 * j / (cols - 1);
          const double f = (1 - s * s) * (1 - t * t);
          g.medial.push_back({0.12 * index + 0.05 * s, 0.05 * t, 0.015 * f});
          g.radius.push_back(0.015 * f);
          g.stiffness.push_back(150.0 + 150.0 * f);
        }
      }
      file.bodies.push_back(std::move(g));
    }
  }
  return file;
}

Vec3 table1_probe(int bodies, double t) {
  const int body = static_cast<int>(t / 0.25) % bodies;
  const double x = 0.12 * body + 0.015 * std::sin(9.0 * t);
  const double y = 0.015 * std::cos(9.0 * t);
  const double press = 0.008 + 0.006 * std::sin(5.0 * t);
  return {x, y, 0.03 - press};
}

}  // namespace palpa::scene
