#include "bench_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "palpa/contact/contact.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/plot/line_plot.hpp"

namespace palpa::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct TestBody {
  std::string name;
  mat::MatBody body;
};

mat::BodyGrid grid_of(int rows, int cols, const std::function<Vec3(double, double)>& skeleton, double r0) {
  mat::BodyGrid g;
  g.id = "bench";
  g.rows = rows;
  g.cols = cols;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double s = static_cast<double>(i) / (rows - 1);
      const double t = static_cast<double>(j) / (cols - 1);
      const Vec3 p = skeleton(s, t);
      g.medial.push_back({p.x(), p.y(), p.z()});
      g.radius.push_back(r0 * 16.0 * s * (1 - s) * t * (1 - t));  // 0 on the boundary
      g.stiffness.push_back(300.0);
    }
  }
  return g;
}

std::vector<TestBody> test_bodies() {
  std::vector<TestBody> out;
  out.push_back({"flat", mat::MatBody::fit(grid_of(9, 9, [](double s, double t) {
                   return Vec3(0.1 * s, 0.1 * t, 0.0);
                 }, 0.02))});
  out.push_back({"curved", mat::MatBody::fit(grid_of(9, 11, [](double s, double t) {
                   const double a = 2 * s - 1, b = 2 * t - 1;
                   return Vec3(0.14 * s, 0.16 * t, 0.025 * (1 - a * a) * (1 - b * b));
                 }, 0.025))});
  // A valley: the skeleton z = (x - 5 cm)^2 / (2 * 2 cm) has a 2 cm radius of curvature at
  // its bottom, about the body's own half thickness, so probes on the concave side come near
  // its centre of curvature, where the distance to the skeleton has several minima.
  out.push_back({"concave", mat::MatBody::fit(grid_of(13, 9, [](double s, double t) {
                   const double x = 0.1 * s - 0.05;
                   return Vec3(0.1 * s, 0.1 * t, x * x / 0.04);
                 }, 0.02))});
  out.push_back({"wavy", mat::MatBody::fit(grid_of(14, 14, [](double s, double t) {
                   return Vec3(0.12 * s, 0.12 * t, 0.012 * std::sin(3 * std::numbers::pi * s) * std::cos(2 * std::numbers::pi * t));
                 }, 0.015))});
  return out;
}

// A palpation-like path: the finger drifts over the body in small loops and presses in
// and out, 0.5 mm per query (about 0.5 m/s at 1 kHz).
std::vector<Vec3> probe_path(const mat::MatBody& body, int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> phase(0.0, 2 * std::numbers::pi);
  const double a = phase(rng), b = phase(rng), c = phase(rng);
  std::vector<Vec3> path;
  std::array<double, mat::kSkeletonChannels> sk;
  for (int k = 0; k < count; ++k) {
    const double t = 0.004 * k;
    const double u = 0.5 + 0.42 * std::sin(0.9 * t + a) + 0.03 * std::sin(7 * t);
    const double v = 0.5 + 0.42 * std::sin(0.7 * t + b) + 0.03 * std::cos(7 * t);
    body.skeleton().evaluate(u, v, sk);
    double n[3];
    mat::skeleton_normal(body.skeleton(), u, v, n);
    // From 1.3 R outside on the top side to 1.3 R on the bottom side and back.
    const double h = 1.3 * std::max(sk[mat::kRadius], 1e-3) * std::sin(0.37 * t + c);
    path.emplace_back(sk[0] + h * n[0], sk[1] + h * n[1], sk[2] + h * n[2]);
  }
  return path;
}

// The high-precision reference: Newton from the best 16 of a dense 96 x 96 sampling.
contact::FootPoint reference_foot(const mat::MatBody& body, const Vec3& q) {
  constexpr int n = 96;
  std::vector<std::pair<double, std::pair<double, double>>> seeds;
  std::array<double, 3> p;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      body.skeleton().evaluate(u, v, p, 3);
      seeds.push_back({(Vec3(p[0], p[1], p[2]) - q).squaredNorm(), {u, v}});
    }
  }
  std::partial_sort(seeds.begin(), seeds.begin() + 16, seeds.end());
  contact::NewtonOptions tight;
  tight.max_iterations = 100;
  tight.parameter_tolerance = 1e-15;
  contact::FootPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int s = 0; s < 16; ++s) {
    const auto f = contact::newton_foot_point(body.skeleton(), q, seeds[static_cast<std::size_t>(s)].second.first,
                                              seeds[static_cast<std::size_t>(s)].second.second, tight);
    if (f.distance < best.distance) best = f;
  }
  return best;
}

template <typename Query>
AccuracyRow measure(const std::string& body_name, const std::string& method, int levels, const mat::MatBody& body,
                    const std::vector<Vec3>& path, const std::vector<contact::Contact>& ref, Query query) {
  std::vector<contact::FootPoint> feet(path.size());
  double best_ns = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 3; ++rep) {  // the fastest of three passes: the host is shared
    const auto start = Clock::now();
    query(feet);
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
                      static_cast<double>(path.size());
    best_ns = std::min(best_ns, ns);
  }
  AccuracyRow row{body_name, method, levels, static_cast<int>(path.size()), best_ns, 0, 0, 0, 0};
  std::vector<double> errors;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const auto c = contact::make_contact(body, feet[k], path[k]);
    const double e = std::abs(c.depth - ref[k].depth);
    errors.push_back(e);
    row.depth_error_max = std::max(row.depth_error_max, e);
    row.param_error_max =
        std::max({row.param_error_max, std::abs(feet[k].u - ref[k].foot.u), std::abs(feet[k].v - ref[k].foot.v)});
    if (c.inside != ref[k].inside) ++row.inside_wrong;
  }
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
  row.depth_error_median = errors[errors.size() / 2];
  return row;
}

void write_csv(const std::vector<AccuracyRow>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << "body,method,levels,queries,ns_per_query,depth_error_max_m,depth_error_median_m,param_error_max,"
         "inside_wrong\n";
  for (const auto& r : rows) {
    out << fmt::format("{},{},{},{},{:.1f},{:.3e},{:.3e},{:.3e},{}\n", r.body, r.method, r.levels, r.queries,
                       r.ns_per_query, r.depth_error_max, r.depth_error_median, r.param_error_max, r.inside_wrong);
  }
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

void write_plot(const std::vector<AccuracyRow>& rows, const std::filesystem::path& path) {
  plot::LinePlot p;
  p.title = "Foot point: time per query vs depth error (max over the path)";
  p.x = {"time per query (ns)", plot::Scale::Log10, {}, {}};
  p.y = {"max depth error (m)", plot::Scale::Log10, {}, {}};
  std::vector<std::string> bodies;
  for (const auto& r : rows)
    if (std::find(bodies.begin(), bodies.end(), r.body) == bodies.end()) bodies.push_back(r.body);
  const plot::Marker markers[] = {plot::Marker::Circle, plot::Marker::Square, plot::Marker::Triangle,
                                  plot::Marker::Cross};
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    plot::Series bisect{bodies[b] + ": bisect k=6..20", {}, {}, markers[b % 4], true};
    plot::Series fast{bodies[b] + ": fast cold, warm", {}, {}, markers[b % 4], false};
    for (const auto& r : rows) {
      if (r.body != bodies[b]) continue;
      // A zero error cannot sit on a log axis: show it at 1e-18 m, below any real error.
      auto& s = r.method == "bisect" ? bisect : fast;
      s.x.push_back(r.ns_per_query);
      s.y.push_back(std::max(r.depth_error_max, 1e-18));
    }
    p.series.push_back(bisect);
    p.series.push_back(fast);
  }
  plot::save_png(p, path);
}

}  // namespace

std::vector<AccuracyRow> run_accuracy_benchmark(const AccuracyOptions& options) {
  std::filesystem::create_directories(options.out);
  std::mt19937 rng(options.seed);
  std::vector<AccuracyRow> rows;
  for (const auto& tb : test_bodies()) {
    const auto& body = tb.body;
    const auto path = probe_path(body, options.probes, rng);
    std::vector<contact::Contact> ref;
    ref.reserve(path.size());
    for (const auto& q : path) ref.push_back(contact::make_contact(body, reference_foot(body, q), q));

    const contact::FootPointSearch search(body.skeleton());
    for (int k = 6; k <= 20; k += 2) {
      rows.push_back(measure(tb.name, "bisect", k, body, path, ref, [&](std::vector<contact::FootPoint>& feet) {
        for (std::size_t i = 0; i < path.size(); ++i) feet[i] = contact::bisect_foot_point(body.skeleton(), path[i], k);
      }));
    }
    rows.push_back(measure(tb.name, "fast-cold", 0, body, path, ref, [&](std::vector<contact::FootPoint>& feet) {
      for (std::size_t i = 0; i < path.size(); ++i) feet[i] = search.closest(body.skeleton(), path[i]);
    }));
    rows.push_back(measure(tb.name, "fast-warm", 0, body, path, ref, [&](std::vector<contact::FootPoint>& feet) {
      feet[0] = search.closest(body.skeleton(), path[0]);
      for (std::size_t i = 1; i < path.size(); ++i) {
        feet[i] = search.closest_from(body.skeleton(), path[i], feet[i - 1].u, feet[i - 1].v);
      }
    }));
  }
  write_csv(rows, options.out / "accuracy.csv");
  write_plot(rows, options.out / "accuracy.png");
  return rows;
}

}  // namespace palpa::cli
