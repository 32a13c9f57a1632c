#include "palpa/engine/scene_snapshot.hpp"

#include <algorithm>

namespace palpa::engine {

SceneSnapshot SceneSnapshot::sized_for(const DrawnScene& drawn) {
  SceneSnapshot s;
  s.bodies.resize(drawn.body_count());
  for (std::size_t b = 0; b < drawn.body_count(); ++b) {
    s.bodies[b].top.assign(drawn.drawn(b).top().control().size(), 0.0);
    s.bodies[b].bottom.assign(drawn.drawn(b).bottom().control().size(), 0.0);
    s.bodies[b].version = ~std::uint64_t{0};  // matches no body version: the first capture copies
  }
  return s;
}

void SceneSnapshot::capture(const DrawnScene& scene, const Sample& last, std::uint64_t tick_number,
                            const LoopEvents& loop_events) {
  tick = tick_number;
  t = last.t;
  probe = last.position;
  force = last.force;
  body = last.body;
  u = last.u;
  v = last.v;
  depth = last.depth;
  fault = last.fault;
  events = loop_events;
  double sum = 0.0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& drawn = scene.drawn(b);
    auto& out = bodies[b];
    // Only a body whose drawn surfaces changed is copied and summed: a refined net has
    // thousands of points, and summing every body at every capture would read them all.
    if (out.version != drawn.version()) {
      std::copy(drawn.top().control().begin(), drawn.top().control().end(), out.top.begin());
      std::copy(drawn.bottom().control().begin(), drawn.bottom().control().end(), out.bottom.begin());
      out.version = drawn.version();
      out.sum = 0.0;
      for (double x : out.top) out.sum += x;
      for (double x : out.bottom) out.sum += x;
    }
    sum += out.sum;
  }
  checksum = sum;
}

double SceneSnapshot::contents_sum() const {
  double sum = 0.0;
  for (const auto& b : bodies) {
    double in_body = 0.0;  // summed in the order capture() sums, so an intact copy matches exactly
    for (double x : b.top) in_body += x;
    for (double x : b.bottom) in_body += x;
    sum += in_body;
  }
  return sum;
}

}  // namespace palpa::engine
