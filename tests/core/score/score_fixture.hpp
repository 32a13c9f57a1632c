#pragma once
// Sessions built in memory for the scoring tests and benchmark: the flat 5 x 5 case
// (data/cases/flat-5x5.json) whose geometry is known in closed form, and samples written
// along paths at a fixed rate.
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "palpa/session/session.hpp"

namespace palpa::test {

/// data/cases/NAME as JSON.
inline nlohmann::json case_document(const std::string& name) {
  std::ifstream in(std::string(PALPA_SOURCE_DIR) + "/data/cases/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

// The flat case: skeleton z = 0 over [-0.05, 0.05]^2 m, x along u, y along v, so
// u = (x + 0.05) / 0.1; radius R = 0.02 (1 - s^2)(1 - t^2), s = x / 0.05, t = y / 0.05;
// the top contour is z = R(x, y).
constexpr double kFlatHalf = 0.05;
constexpr double kFlatR0 = 0.02;

inline double flat_radius(double x, double y) {
  const double s = x / kFlatHalf, t = y / kFlatHalf;
  return kFlatR0 * (1 - s * s) * (1 - t * t);
}
inline double flat_u(double x) { return (x + kFlatHalf) / (2 * kFlatHalf); }

/// Area of the flat case's top contour over x in [x0, x1], y in [-0.05, 0.05]:
/// the integral of sqrt(1 + R_x^2 + R_y^2) by the midpoint rule on a fine grid.
inline double flat_top_area(double x0 = -kFlatHalf, double x1 = kFlatHalf, int n = 800) {
  double sum = 0.0;
  const double hx = (x1 - x0) / n, hy = 2 * kFlatHalf / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (i + 0.5) * hx, y = -kFlatHalf + (j + 0.5) * hy;
      const double s = x / kFlatHalf, t = y / kFlatHalf;
      const double rx = kFlatR0 * (-2 * s / kFlatHalf) * (1 - t * t);
      const double ry = kFlatR0 * (1 - s * s) * (-2 * t / kFlatHalf);
      sum += std::sqrt(1 + rx * rx + ry * ry) * hx * hy;
    }
  }
  return sum;
}

/// The flat case with tumours {x, y, z, radius} (stiffness 1500 N/m) and extra root fields.
inline nlohmann::json flat_case(const std::vector<std::array<double, 4>>& tumours = {},
                                const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json doc = case_document("flat-5x5.json");
  if (!tumours.empty()) {
    doc["tumors"] = nlohmann::json::array();
    for (const auto& t : tumours)
      doc["tumors"].push_back({{"body", "flat"}, {"center", {t[0], t[1], t[2]}}, {"radius", t[3]}, {"stiffness", 1500.0}});
  }
  for (const auto& [key, value] : extra.items()) doc[key] = value;
  return doc;
}

/// Builds a session at `rate` Hz: samples are appended with a clock that advances 1/rate.
class SessionBuilder {
 public:
  explicit SessionBuilder(nlohmann::json doc, double rate = 1000.0) {
    s_.info.case_document = std::move(doc);
    s_.info.rate_hz = rate;
    s_.info.trainee = "test";
    dt_ = 1.0 / rate;
  }
  double now() const { return t_; }

  /// One tick in contact with body 0 on the flat case at (x, y): depth in m, |F| in N
  /// (pointing up).
  void flat_contact(double x, double y, double depth, double force) {
    engine::Sample s;
    s.t = t_;
    s.position = {x, y, flat_radius(x, y) - depth};
    s.force = {0.0, 0.0, force};
    s.body = 0;
    s.u = flat_u(x);
    s.v = flat_u(y);
    s.depth = depth;
    s_.samples.push_back(s);
    t_ += dt_;
  }
  /// One tick in contact at parameters (u, v) of body `body` (any case).
  void contact_uv(int body, double u, double v, double depth, double force) {
    engine::Sample s;
    s.t = t_;
    s.force = {0.0, 0.0, force};
    s.body = body;
    s.u = u;
    s.v = v;
    s.depth = depth;
    s_.samples.push_back(s);
    t_ += dt_;
  }
  /// One tick off the tissue.
  void air(double force = 0.0, bool fault = false) {
    engine::Sample s;
    s.t = t_;
    s.position = {0.0, 0.0, 0.1};
    s.force = {0.0, 0.0, force};
    s.fault = fault;
    s_.samples.push_back(s);
    t_ += dt_;
  }
  /// Slides in contact from (x0, y0) to (x1, y1) at `speed` m/s.
  void slide(double x0, double y0, double x1, double y1, double speed, double depth, double force) {
    const double length = std::hypot(x1 - x0, y1 - y0);
    const int n = std::max(1, static_cast<int>(std::ceil(length / (speed * dt_))));
    for (int k = 0; k < n; ++k) {
      const double a = k / double(n);
      flat_contact(x0 + a * (x1 - x0), y0 + a * (y1 - y0), depth, force);
    }
  }
  void event(session::EventKind kind, std::int64_t mark = -1, std::array<double, 3> position = {}) {
    session::Event e;
    e.t = t_;
    e.kind = kind;
    e.mark = mark;
    e.position = position;
    s_.events.push_back(e);
  }
  void mark(std::int64_t id, double x, double y, double depth = 0.002) {
    event(session::EventKind::Mark, id, {x, y, flat_radius(x, y) - depth});
  }
  /// Start at the first tick, End after the last: a complete session.
  session::Session finish(bool complete = true) {
    session::Session out = s_;
    session::Event start;
    start.t = 0.0;
    start.kind = session::EventKind::Start;
    out.events.insert(out.events.begin(), start);
    if (complete) {
      session::Event end;
      end.t = t_;
      end.kind = session::EventKind::End;
      out.events.push_back(end);
    }
    out.complete = complete;
    return out;
  }

 private:
  session::Session s_;
  double t_ = 0.0;
  double dt_ = 1e-3;
};

}  // namespace palpa::test
