#pragma once
// Triangle meshes of the analytic bodies (analytic_bodies.hpp): the skin as an open
// height-field patch over the footprint, the support as a plane patch, and the body closed
// on its base (top and bottom sheets sharing their border).
#include <functional>

#include "analytic_bodies.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"

namespace palpa::anatomy::testing {

/// The surface z = f(x, y) over [-half, half]^2 in steps of `step`, keeping the triangles
/// `keep` accepts (by their vertices' (x, y)).
inline TriangleMesh height_mesh(const std::function<double(double, double)>& f, double half, double step,
                                const std::function<bool(double, double)>& keep = nullptr, bool other_diagonal = false) {
  TriangleMesh mesh;
  const int n = static_cast<int>(std::round(2.0 * half / step)) + 1;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double x = -half + a * step, y = -half + b * step;
      mesh.points.push_back({x, y, f(x, y)});
    }
  }
  const auto id = [n](int a, int b) { return static_cast<std::int32_t>(a + n * b); };
  for (int b = 0; b + 1 < n; ++b) {
    for (int a = 0; a + 1 < n; ++a) {
      const double x = -half + (a + 0.5) * step, y = -half + (b + 0.5) * step;
      if (keep && !keep(x, y)) continue;
      if (other_diagonal) {
        mesh.triangles.push_back({id(a, b), id(a + 1, b), id(a, b + 1)});
        mesh.triangles.push_back({id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)});
      } else {
        mesh.triangles.push_back({id(a, b), id(a + 1, b), id(a + 1, b + 1)});
        mesh.triangles.push_back({id(a, b), id(a + 1, b + 1), id(a, b + 1)});
      }
    }
  }
  return mesh;
}

/// The skin of `body` over its footprint (plus a cell all round), 1 mm triangles.
inline TriangleMesh skin_mesh(const AnalyticBody& body, double step = 1e-3) {
  return height_mesh([&](double x, double y) { return body.top(x, y); }, body.half_x, step,
                     [&](double x, double y) {
                       for (double dx : {-step, 0.0, step}) {
                         for (double dy : {-step, 0.0, step}) {
                           if (body.thickness(x + dx, y + dy) > 0.0) return true;
                         }
                       }
                       return false;
                     });
}

/// The support of `body` as a patch over the whole square, 4 mm triangles.
inline TriangleMesh support_mesh(const AnalyticBody& body) { return height_mesh(body.support, body.half_x, 4e-3); }

/// The body closed on its support: the skin sheet over the whole square and the support sheet
/// under it, the border's points shared, the bottom's triangles turned over and split along
/// the other diagonal (so that no corner diagonal is shared by four triangles).
inline TriangleMesh closed_mesh(const AnalyticBody& body, double step = 1e-3) {
  TriangleMesh top = height_mesh([&](double x, double y) { return body.top(x, y); }, body.half_x, step);
  const TriangleMesh bottom = height_mesh(body.support, body.half_x, step, nullptr, true);
  const int n = static_cast<int>(std::round(2.0 * body.half_x / step)) + 1;
  const auto border = [n](int k) { const int a = k % n, b = k / n; return a == 0 || b == 0 || a == n - 1 || b == n - 1; };
  std::vector<std::int32_t> remap(bottom.points.size());
  for (std::size_t k = 0; k < bottom.points.size(); ++k) {
    if (border(static_cast<int>(k))) {
      remap[k] = static_cast<std::int32_t>(k);  // the same point as the top sheet's border
    } else {
      remap[k] = static_cast<std::int32_t>(top.points.size());
      top.points.push_back(bottom.points[k]);
    }
  }
  for (const auto& t : bottom.triangles) top.triangles.push_back({remap[static_cast<std::size_t>(t[0])], remap[static_cast<std::size_t>(t[2])], remap[static_cast<std::size_t>(t[1])]});
  return top;
}

}  // namespace palpa::anatomy::testing
