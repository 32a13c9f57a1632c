// The support and the free surface of triangle meshes, column by column along the
// support's normal (docs/anatomy-import.md, "Surface meshes").
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mesh_columns.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"
#include "support_model.hpp"

namespace palpa::anatomy {

namespace {

// Samples across the larger side of the body at most.
constexpr int kMaxSamples = 1024;

void check_mesh(const TriangleMesh& mesh, const std::string& source) {
  if (mesh.triangles.empty()) throw ImportError(source + ": the mesh has no triangles");
}

Vec3 centroid(const TriangleMesh& mesh) {
  Vec3 c = Vec3::Zero();
  for (const auto& p : mesh.points) c += to_vec3(p);
  return c / static_cast<double>(std::max<std::size_t>(mesh.points.size(), 1));
}

// Both fields over the projection of `mesh` plus two samples all round.
void size_fields(const TriangleMesh& mesh, SurfacePair& pair) {
  double s_lo = 1e300, s_hi = -1e300, t_lo = 1e300, t_hi = -1e300;
  for (const auto& p : mesh.points) {
    const Vec3 q = pair.frame.to_local(to_vec3(p));
    s_lo = std::min(s_lo, q.x()), s_hi = std::max(s_hi, q.x());
    t_lo = std::min(t_lo, q.y()), t_hi = std::max(t_hi, q.y());
  }
  const double step = std::max(pair.resolution, std::max(s_hi - s_lo, t_hi - t_lo) / kMaxSamples);
  for (HeightField* field : {&pair.bottom, &pair.top}) {
    field->step = step;
    field->s0 = s_lo - 2.0 * step;
    field->t0 = t_lo - 2.0 * step;
    field->ns = static_cast<int>(std::ceil((s_hi - s_lo) / step)) + 5;
    field->nt = static_cast<int>(std::ceil((t_hi - t_lo) / step)) + 5;
    field->h.assign(static_cast<std::size_t>(field->ns) * static_cast<std::size_t>(field->nt), kNoSurface);
  }
}

// The free surface's height over a column from the skin's crossings above `bottom`: one
// crossing is the skin itself, however thin the tissue; of two, the lower one is the skin's
// underside when it lies within `near` of the support (a closed skin resting on it). Any
// other crossing is an overhang.
double skin_height(std::vector<double> hits, double bottom, double near, const Frame& f, double s, double t,
                   const std::string& source) {
  hits.erase(std::remove_if(hits.begin(), hits.end(), [&](double h) { return h < bottom - near; }), hits.end());
  if (hits.size() == 2 && hits.front() <= bottom + near) hits.erase(hits.begin());
  if (hits.size() > 1) {
    throw ImportError(fmt::format("{}: overhang at {}: the skin crosses this line along the support's normal more "
                                  "than once; the free surface must be a height field over the support",
                                  source, millimetres(f.to_world(s, t, hits[1]))));
  }
  return hits.empty() ? bottom : std::max(bottom, hits.front());
}

}  // namespace

SurfacePair surfaces_from_meshes(const TriangleMesh& skin, const TriangleMesh& support, const std::string& skin_source,
                                 const std::string& support_source) {
  check_mesh(skin, skin_source);
  check_mesh(support, support_source);
  check_edges(skin, false, skin_source);
  check_edges(support, false, support_source);
  SurfacePair pair;
  pair.resolution = median_edge(skin);
  std::vector<Vec3> support_points;
  for (const auto& p : support.points) support_points.push_back(to_vec3(p));
  SupportModel model;
  try {
    model = fit_support(support_points, centroid(skin), pair.resolution);
  } catch (const ImportError& e) {
    throw ImportError(support_source + ": " + e.what());
  }
  pair.frame = model.frame;
  pair.support_kind = model.curved ? "curved" : "plane";
  size_fields(skin, pair);
  const ColumnCaster skin_cast(skin, pair.frame, 4.0 * pair.top.step), support_cast(support, pair.frame, 4.0 * pair.top.step);
  const double near = std::max(2.0 * pair.resolution, 1e-3);
  std::vector<double> hits;
  for (int b = 0; b < pair.top.nt; ++b) {
    for (int a = 0; a < pair.top.ns; ++a) {
      const double s = pair.top.s_at(a), t = pair.top.t_at(b);
      support_cast.heights(s, t, hits);
      const double bottom = hits.empty() ? model.height(s, t) : hits.back();
      skin_cast.heights(s, t, hits);
      pair.bottom.at(a, b) = bottom;
      pair.top.at(a, b) = skin_height(hits, bottom, near, pair.frame, s, t, skin_source);
    }
  }
  return pair;
}

SurfacePair surfaces_from_closed_mesh(const TriangleMesh& mesh, const Vec3& normal, double offset,
                                      const std::string& source) {
  check_mesh(mesh, source);
  check_edges(mesh, true, source);
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(offset)) throw ImportError("--support-plane: the normal must not be zero");
  Vec3 n = normal / length;
  Vec3 origin = -offset / length * n;
  if (n.dot(centroid(mesh) - origin) < 0.0) n = -n;
  SurfacePair pair;
  pair.frame = frame_with_normal(origin, n);
  pair.resolution = median_edge(mesh);
  size_fields(mesh, pair);
  const ColumnCaster cast(mesh, pair.frame, 4.0 * pair.top.step);
  const double near = std::max(2.0 * pair.resolution, 1e-3);
  std::vector<double> hits;
  for (int b = 0; b < pair.top.nt; ++b) {
    for (int a = 0; a < pair.top.ns; ++a) {
      const double s = pair.top.s_at(a), t = pair.top.t_at(b);
      cast.heights(s, t, hits);
      if (!hits.empty() && std::abs(hits.front()) > near) {
        throw ImportError(fmt::format("{}: the underside is {:.1f} mm {} the support plane at {}; it must lie on it",
                                      source, std::abs(hits.front()) * 1e3, hits.front() > 0 ? "above" : "below",
                                      millimetres(pair.frame.to_world(s, t, hits.front()))));
      }
      // The underside on the plane, then the skin (a single crossing: where the two meet).
      if (hits.size() >= 2) hits.erase(hits.begin());
      pair.bottom.at(a, b) = 0.0;
      pair.top.at(a, b) = skin_height(hits, 0.0, near, pair.frame, s, t, source);
    }
  }
  return pair;
}

}  // namespace palpa::anatomy
