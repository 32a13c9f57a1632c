#include "mesh_columns.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"

namespace palpa::anatomy {

ColumnCaster::ColumnCaster(const TriangleMesh& mesh, const Frame& frame, double bin) : mesh_(mesh), bin_(bin) {
  local_.reserve(mesh.points.size());
  double s_hi = -1e300, t_hi = -1e300;
  s0_ = t0_ = 1e300;
  for (const auto& p : mesh.points) {
    local_.push_back(frame.to_local(to_vec3(p)));
    s0_ = std::min(s0_, local_.back().x());
    t0_ = std::min(t0_, local_.back().y());
    s_hi = std::max(s_hi, local_.back().x());
    t_hi = std::max(t_hi, local_.back().y());
  }
  ns_ = std::max(1, static_cast<int>((s_hi - s0_) / bin_) + 1);
  nt_ = std::max(1, static_cast<int>((t_hi - t0_) / bin_) + 1);
  bins_.resize(static_cast<std::size_t>(ns_) * static_cast<std::size_t>(nt_));
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& tri = mesh.triangles[k];
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const int v : tri) {
      const Vec3& q = local_[static_cast<std::size_t>(v)];
      lo[0] = std::min(lo[0], q.x()), hi[0] = std::max(hi[0], q.x());
      lo[1] = std::min(lo[1], q.y()), hi[1] = std::max(hi[1], q.y());
    }
    const int a0 = std::clamp(static_cast<int>((lo[0] - s0_) / bin_), 0, ns_ - 1);
    const int a1 = std::clamp(static_cast<int>((hi[0] - s0_) / bin_), 0, ns_ - 1);
    const int b0 = std::clamp(static_cast<int>((lo[1] - t0_) / bin_), 0, nt_ - 1);
    const int b1 = std::clamp(static_cast<int>((hi[1] - t0_) / bin_), 0, nt_ - 1);
    for (int b = b0; b <= b1; ++b) {
      for (int a = a0; a <= a1; ++a) bins_[static_cast<std::size_t>(a + ns_ * b)].push_back(static_cast<int>(k));
    }
  }
}

void ColumnCaster::heights(double s, double t, std::vector<double>& out) const {
  out.clear();
  const int a = static_cast<int>(std::floor((s - s0_) / bin_)), b = static_cast<int>(std::floor((t - t0_) / bin_));
  if (a < 0 || b < 0 || a >= ns_ || b >= nt_) return;
  for (const int k : bins_[static_cast<std::size_t>(a + ns_ * b)]) {
    const auto& tri = mesh_.triangles[static_cast<std::size_t>(k)];
    const Vec3 &p = local_[static_cast<std::size_t>(tri[0])], &q = local_[static_cast<std::size_t>(tri[1])],
               &r = local_[static_cast<std::size_t>(tri[2])];
    // Barycentric coordinates of (s, t) in the projected triangle; on its edges counts as in.
    const double det = (q.x() - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (q.y() - p.y());
    if (std::abs(det) < 1e-24) continue;
    const double l1 = ((s - p.x()) * (r.y() - p.y()) - (r.x() - p.x()) * (t - p.y())) / det;
    const double l2 = ((q.x() - p.x()) * (t - p.y()) - (s - p.x()) * (q.y() - p.y())) / det;
    constexpr double kEdge = -1e-12;
    if (l1 < kEdge || l2 < kEdge || 1.0 - l1 - l2 < kEdge) continue;
    out.push_back(p.z() + l1 * (q.z() - p.z()) + l2 * (r.z() - p.z()));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end(), [](double x, double y) { return y - x < 1e-9; }), out.end());
}

void check_edges(const TriangleMesh& mesh, bool closed, const std::string& source) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(mesh.triangles.size() * 3);
  auto key = [](std::int32_t a, std::int32_t b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
           static_cast<std::uint32_t>(std::max(a, b));
  };
  for (const auto& tri : mesh.triangles) {
    for (int e = 0; e < 3; ++e) ++uses[key(tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)])];
  }
  std::size_t border = 0;
  std::uint64_t first_border = 0;
  for (const auto& [edge, count] : uses) {
    const Vec3 mid = 0.5 * (to_vec3(mesh.points[edge >> 32]) + to_vec3(mesh.points[edge & 0xffffffffu]));
    if (count > 2) {
      throw ImportError(fmt::format("{}: non-manifold: the edge at {} is shared by {} triangles", source,
                                    millimetres(mid), count));
    }
    if (count == 1 && border++ == 0) first_border = edge;
  }
  if (closed && border > 0) {
    const Vec3 mid =
        0.5 * (to_vec3(mesh.points[first_border >> 32]) + to_vec3(mesh.points[first_border & 0xffffffffu]));
    throw ImportError(fmt::format("{}: open mesh: {} edges belong to one triangle only (one at {}); a closed surface "
                                  "is needed with --support-plane",
                                  source, border, millimetres(mid)));
  }
}

double median_edge(const TriangleMesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    lengths.push_back((to_vec3(mesh.points[static_cast<std::size_t>(tri[0])]) -
                       to_vec3(mesh.points[static_cast<std::size_t>(tri[1])]))
                          .norm());
  }
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  return lengths[lengths.size() / 2];
}

}  // namespace palpa::anatomy
