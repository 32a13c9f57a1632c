// palpa-cli bench tessellation: triangles, time and deviation of the display tessellation
// against its tolerance, for the first body of a case at rest, pressed, and pressed as the
// trainee window draws it (refined to fingertip-sized spans), beside the uniform grid the
// tessellation used before its grid followed the knots.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bench_suites.hpp"
#include "commands.hpp"
#include "palpa/deform/deformed_body.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/plot/line_plot.hpp"
#include "palpa/render/tessellation.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct Row {
  std::string state;  ///< "rest", "pressed" or "drawn" (pressed, on the display net)
  double tolerance = 0.0;
  std::array<int, 2> segments_u{}, segments_v{};  ///< top, bottom
  std::size_t triangles = 0;                       ///< both contours
  std::size_t uniform_triangles = 0;               ///< the cheapest uniform grid within the same bound
  double ms_per_body = 0.0;                        ///< median, both contours
  double max_deviation = 0.0;                      ///< m, over both contours
  double bound = 0.0;                              ///< m, the larger a-priori bound of the two
  bool within = false;
};

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Triangles of the uniform grid with the fewest cells whose bound over the surface's
/// global derivative bounds is within tol (at most max_segments per direction; the cap
/// when none is), by brute force.
std::size_t uniform_triangles(const spline::BSplineSurface& s, double tol) {
  const int limit = render::TessellationOptions{}.max_segments;
  const auto b = render::second_derivative_bounds(s);
  const double ru = s.knots_u().back() - s.knots_u().front(), rv = s.knots_v().back() - s.knots_v().front();
  long best = long{limit} * limit;
  for (int nu = 1; nu <= limit; ++nu) {
    int nv = 1;
    while (nv <= limit && render::grid_error_bound(b, ru, rv, nu, nv) > tol) ++nv;
    if (nv <= limit) best = std::min(best, long{nu} * nv);
  }
  return static_cast<std::size_t>(2 * best);
}

/// Tessellates top and bottom at one tolerance: the median time of repeated runs into
/// meshes that already have their storage (what the display does every frame), then the
/// deviation, measured by sampling every triangle at 15 barycentric points.
Row measure(const std::string& state, const spline::BSplineSurface& top, const spline::BSplineSurface& bottom,
            double tolerance) {
  render::TessellationOptions o;
  o.tolerance = tolerance;
  render::Mesh mt, mb;
  auto run = [&] {
    render::tessellate(top, o, false, mt);
    render::tessellate(bottom, o, true, mb);
  };
  run();  // sizes the meshes
  const auto t0 = Clock::now();
  run();
  const double once = std::max(ms_since(t0), 1e-6);
  const int reps = std::clamp(static_cast<int>(300.0 / once), 5, 501);  // about 0.3 s per tolerance
  std::vector<double> times(static_cast<std::size_t>(reps));
  for (auto& t : times) {
    const auto t1 = Clock::now();
    run();
    t = ms_since(t1);
  }
  std::nth_element(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2), times.end());

  Row r;
  r.state = state;
  r.tolerance = tolerance;
  r.segments_u = {mt.rows - 1, mb.rows - 1};
  r.segments_v = {mt.cols - 1, mb.cols - 1};
  r.triangles = mt.triangle_count() + mb.triangle_count();
  r.uniform_triangles = uniform_triangles(top, tolerance) + uniform_triangles(bottom, tolerance);
  r.ms_per_body = times[times.size() / 2];
  r.max_deviation =
      std::max(render::max_parametric_deviation(mt, top, 4), render::max_parametric_deviation(mb, bottom, 4));
  r.bound = std::max(mt.error_bound, mb.error_bound);
  r.within = r.max_deviation <= tolerance;
  return r;
}

/// The probe 10 mm below the top surface over the middle of the skeleton (u = v = 1/2).
palpa::Vec3 probe_below_top(const mat::MatBody& body, double depth) {
  std::array<double, mat::kSkeletonChannels> sk{};
  body.skeleton().evaluate(0.5, 0.5, sk);
  double n[3] = {0.0, 0.0, 1.0};
  if (!mat::skeleton_normal(body.skeleton(), 0.5, 0.5, n)) throw std::runtime_error("no skeleton normal at (0.5, 0.5)");
  const palpa::Vec3 normal(n[0], n[1], n[2]);
  return palpa::Vec3(sk[mat::kX], sk[mat::kY], sk[mat::kZ]) + (std::max(0.0, sk[mat::kRadius]) - depth) * normal;
}

/// Time of BodyMeshes::update for a body pressed anew before every update (its version
/// changes each time): the display's cost per frame for one moving body. Median, ms.
double ms_per_update(deform::DeformedBody& body, const contact::Contact& c, const palpa::Vec3& q) {
  render::BodyMeshes meshes;
  const render::TessellationOptions o;
  std::vector<double> times(201);
  for (std::size_t k = 0; k < times.size() + 5; ++k) {
    // Alternate between two press depths so that the surfaces really change.
    const palpa::Vec3 qk = q + (k % 2 == 0 ? 0.0 : 0.001) * c.outward;
    body.press(c, qk);
    const auto t0 = Clock::now();
    meshes.update(body, o);
    if (k >= 5) times[k - 5] = ms_since(t0);  // the first updates size the meshes
  }
  std::nth_element(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2), times.end());
  body.press(c, q);
  return times[times.size() / 2];
}

void write_csv(const std::vector<Row>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << "state,tolerance_m,segments_u,segments_v,triangles,ms_per_body,max_deviation_m,within,uniform_triangles\n";
  for (const auto& r : rows) {
    out << fmt::format("{},{:.3e},{},{},{},{:.4f},{:.3e},{},{}\n", r.state, r.tolerance,
                       std::max(r.segments_u[0], r.segments_u[1]), std::max(r.segments_v[0], r.segments_v[1]),
                       r.triangles, r.ms_per_body, r.max_deviation, r.within ? 1 : 0, r.uniform_triangles);
  }
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

void write_png(const std::vector<Row>& rows, const std::filesystem::path& path) {
  const std::array<std::string, 3> states{"rest", "pressed", "drawn"};
  const std::array<plot::Marker, 3> markers{plot::Marker::Circle, plot::Marker::Square, plot::Marker::Triangle};
  auto panel = [&](const std::string& title, const std::string& ylabel, auto value) {
    plot::LinePlot p;
    p.title = title;
    p.x = {"tolerance (m)", plot::Scale::Log10, {}, {}};
    p.y = {ylabel, plot::Scale::Log10, {}, {}};
    p.width = 700;
    p.height = 520;
    for (std::size_t s = 0; s < states.size(); ++s) {
      plot::Series series{states[s], {}, {}, markers[s], true};
      for (const auto& r : rows) {
        if (r.state != states[s]) continue;
        series.x.push_back(r.tolerance);
        series.y.push_back(value(r));
      }
      if (!series.x.empty()) p.series.push_back(std::move(series));
    }
    return p;
  };
  auto triangles = panel("Triangles (top + bottom)", "triangles",
                         [](const Row& r) { return static_cast<double>(r.triangles); });
  auto time = panel("Time per body (median)", "ms per body", [](const Row& r) { return r.ms_per_body; });
  auto deviation = panel("Max deviation from the surface", "max deviation (m)", [](const Row& r) {
    return std::max(r.max_deviation, 1e-12);  // a log axis cannot show 0
  });
  double lo = 1.0, hi = 0.0;
  for (const auto& r : rows) lo = std::min(lo, r.tolerance), hi = std::max(hi, r.tolerance);
  deviation.series.push_back({"y = x (the tolerance)", {lo, hi}, {lo, hi}, plot::Marker::None, true});

  cv::Mat image;
  cv::hconcat(std::vector<cv::Mat>{plot::render(triangles), plot::render(time), plot::render(deviation)}, image);
  if (!cv::imwrite(path.string(), image)) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace

int run_bench_tessellation(const std::filesystem::path& out_dir, const std::filesystem::path& case_path) {
  std::unique_ptr<scene::Scene> scene;
  try {
    scene = std::make_unique<scene::Scene>(scene::Scene::build(io::load_case(case_path), case_path.string()));
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }
  if (scene->size() == 0) {
    print_error(case_path.string() + ": the case has no body");
    return kBadInput;
  }
  std::filesystem::create_directories(out_dir);
  const auto& rest = scene->body(0).body;

  // The body pressed 10 mm in over the middle of its skeleton.
  deform::DeformedBody pressed(rest);
  deform::DeformedBody drawn(rest, engine::EngineOptions{}.deform);  // as the trainee window draws it
  const palpa::Vec3 q = probe_below_top(rest, 0.010);
  auto state = scene->make_state();
  const auto hit = scene->probe(q, state);
  const bool have_press = hit.body == 0;
  if (have_press) {
    pressed.press(hit.contact, q);
    drawn.press(hit.contact, q);
  } else {
    std::printf("note: the probe 10 mm below the top is not inside body '%s': pressed rows skipped\n",
                rest.id().c_str());
  }

  // 1e-2 .. 1e-6 m, two per decade, and the default tolerance.
  std::vector<double> tolerances;
  for (int k = 0; k <= 8; ++k) tolerances.push_back(std::pow(10.0, -2.0 - 0.5 * k));
  tolerances.push_back(render::TessellationOptions{}.tolerance);
  std::sort(tolerances.rbegin(), tolerances.rend());

  std::vector<Row> rows;
  for (double tol : tolerances) rows.push_back(measure("rest", rest.top(), rest.bottom(), tol));
  if (have_press) {
    for (double tol : tolerances) rows.push_back(measure("pressed", pressed.top(), pressed.bottom(), tol));
    for (double tol : tolerances) rows.push_back(measure("drawn", drawn.top(), drawn.bottom(), tol));
  }
  write_csv(rows, out_dir / "tessellation.csv");
  write_png(rows, out_dir / "tessellation.png");

  std::printf("body '%s'; segments u x v for top / bottom; deviation sampled at 15 points per triangle\n",
              rest.id().c_str());
  std::printf("%-8s %11s %17s %10s %10s %11s %13s %13s %6s\n", "state", "tolerance m", "segments t / b",
              "triangles", "uniform", "ms per body", "max dev m", "bound m", "within");
  for (const auto& r : rows) {
    const std::string segs =
        fmt::format("{}x{} / {}x{}", r.segments_u[0], r.segments_v[0], r.segments_u[1], r.segments_v[1]);
    std::printf("%-8s %11.2e %17s %10zu %10zu %11.4f %13.3e %13.3e %6s\n", r.state.c_str(), r.tolerance, segs.c_str(),
                r.triangles, r.uniform_triangles, r.ms_per_body, r.max_deviation, r.bound, r.within ? "yes" : "NO");
  }
  if (have_press) {
    std::printf("re-tessellating the pressed body after each press (BodyMeshes::update, default tolerance %.1e m): "
                "%.3f ms (median)\n",
                render::TessellationOptions{}.tolerance, ms_per_update(pressed, hit.contact, q));
  }
  std::printf("wrote %s and %s\n", (out_dir / "tessellation.csv").c_str(), (out_dir / "tessellation.png").c_str());
  return kOk;
}

}  // namespace palpa::cli
