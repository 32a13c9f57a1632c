#include "palpa/score/nearest_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include <nanoflann.hpp>

namespace palpa::score {
namespace {

// nanoflann's view of a point set.
struct Points {
  const std::vector<Vec3>& p;
  std::size_t kdtree_get_point_count() const { return p.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return p[i][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;  // let the tree compute it
  }
};

bool before(const Vec3& a, const Vec3& b) {
  return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
}

// The finite points of p, each once (sorted: `before` is a strict order on finite points only).
std::vector<Vec3> distinct(std::vector<Vec3> p) {
  p.erase(std::remove_if(p.begin(), p.end(), [](const Vec3& x) { return !x.allFinite(); }), p.end());
  std::sort(p.begin(), p.end(), before);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, std::size_t>;

}  // namespace

std::vector<double> nearest_distances(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  std::vector<double> out;
  // Each point once: a tree over many copies of one point (a session jumping across a body
  // on one line puts every midpoint there) visits every copy, each tied at the same
  // distance, and so does a query repeated. Copies change no nearest distance.
  const std::vector<Vec3> targets = distinct(to);
  if (targets.empty()) return out;
  const Points points{targets};
  const Tree tree(3, points, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  out.assign(from.size(), std::numeric_limits<double>::quiet_NaN());  // a point not finite has no distance
  std::vector<std::size_t> order;
  order.reserve(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    if (from[k].allFinite()) order.push_back(k);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return before(from[a], from[b]); });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Vec3& q = from[order[k]];
    if (k > 0 && q == from[order[k - 1]]) {
      out[order[k]] = out[order[k - 1]];
      continue;
    }
    std::size_t index = 0;
    double squared = 0.0;
    nanoflann::KNNResultSet<double, std::size_t> nearest(1);
    nearest.init(&index, &squared);
    tree.findNeighbors(nearest, q.data(), nanoflann::SearchParams());
    out[order[k]] = std::sqrt(squared);
  }
  return out;
}

}  // namespace palpa::score
