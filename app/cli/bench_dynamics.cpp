#include "bench_dynamics.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "palpa/deform/control_point_modification.hpp"
#include "palpa/deform/oscillator.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/plot/line_plot.hpp"

namespace palpa::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The analytic damped oscillator (under-damped), written out in long double: the truth
// every integrator is measured against.
long double analytic_x(long double k, long double b, long double m, long double x0, long double v0, long double t) {
  const long double alpha = b / (2 * m);
  const long double wd = std::sqrt(k / m - alpha * alpha);
  return std::exp(-alpha * t) * (x0 * std::cos(wd * t) + (v0 + alpha * x0) / wd * std::sin(wd * t));
}

struct Integrator {
  const char* name;
  // advances (x, v) by dt for m x'' + b x' + k x = 0
  void (*step)(double k, double b, double m, double dt, const deform::OscillatorStep& exact, double& x, double& v);
};

const Integrator kIntegrators[] = {
    {"exact (Palpa)",
     [](double, double, double, double, const deform::OscillatorStep& e, double& x, double& v) { e.apply(x, v); }},
    {"implicit Euler",
     [](double k, double b, double m, double dt, const deform::OscillatorStep&, double& x, double& v) {
       // (m + b dt + k dt^2) v1 = m v - k dt x;  x1 = x + dt v1
       const double v1 = (m * v - k * dt * x) / (m + b * dt + k * dt * dt);
       x += dt * v1;
       v = v1;
     }},
    {"semi-implicit Euler",
     [](double k, double b, double m, double dt, const deform::OscillatorStep&, double& x, double& v) {
       v += dt * (-k * x - b * v) / m;
       x += dt * v;
     }},
    {"explicit Euler",
     [](double k, double b, double m, double dt, const deform::OscillatorStep&, double& x, double& v) {
       const double a = (-k * x - b * v) / m;
       x += dt * v;
       v += dt * a;
     }},
};

struct DynamicsRow {
  std::string integrator;
  double dt;
  double max_error;   // m, over 0.2 s, x0 = 1 mm
  double ns_per_step;  // one control point (x, y, z) advanced by one step
  bool stable;        // final energy <= initial
};

std::vector<DynamicsRow> integrator_sweep() {
  // A skin-like control point: 300 N/m, 1 g, damping ratio 0.2 (lightly damped, so
  // phase errors show): w0 = 548 rad/s.
  const double k = 300.0;
  const double m = 1e-3;
  const double b = deform::damping_for_ratio(k, m, 0.2);
  const double x0 = 1e-3;
  const double horizon = 0.2;
  std::vector<DynamicsRow> rows;
  for (const auto& integ : kIntegrators) {
    for (double dt : {1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2}) {
      const auto exact = deform::OscillatorStep::exact(k, b, m, dt);
      const int steps = static_cast<int>(std::lround(horizon / dt));
      double x = x0;
      double v = 0.0;
      double err = 0.0;
      for (int s = 1; s <= steps; ++s) {
        integ.step(k, b, m, dt, exact, x, v);
        const double truth = static_cast<double>(analytic_x(k, b, m, x0, 0.0, static_cast<long double>(s) * dt));
        err = std::max(err, std::isfinite(x) ? std::abs(x - truth) : std::numeric_limits<double>::infinity());
      }
      // Timing apart from the truth: 10^6 steps of one control point's three components,
      // restarted every 100 steps so the values never decay into (slow) subnormals.
      double tx = x0, tv = 0.0, ty = x0, tw = 0.0, tz = x0, tq = 0.0;
      const auto start = Clock::now();
      for (int r = 0; r < 10000; ++r) {
        tx = ty = tz = x0;
        tv = tw = tq = 0.0;
        for (int s = 0; s < 100; ++s) {
          integ.step(k, b, m, dt, exact, tx, tv);
          integ.step(k, b, m, dt, exact, ty, tw);
          integ.step(k, b, m, dt, exact, tz, tq);
        }
      }
      const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count() / 1e6;
      if (!std::isfinite(tx + ty + tz + tv + tw + tq)) tx = 0.0;  // keep the loop observable
      const double energy = 0.5 * (m * v * v + k * x * x);
      rows.push_back({integ.name, dt, err, ns, std::isfinite(energy) && energy <= 0.5 * k * x0 * x0});
    }
  }
  return rows;
}

struct ModificationRow {
  int pu, pv;
  double landing_error;  // |S_new(u,v) - (S(u,v) + D)| / |D|
  double max_control;    // max |dP| / |D|
  double overshoot;      // max over the surface of |S_new - S| / |D| (1 = no bump beyond the target)
  double ns;             // per modification
};

std::vector<ModificationRow> modification_sweep() {
  // A 16 x 16 flat bicubic patch; displace points at mid-span and at a knot.
  mat::BodyGrid g;
  g.id = "patch";
  g.rows = 16;
  g.cols = 16;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      g.medial.push_back({0.01 * i, 0.01 * j, 0.0});
      g.radius.push_back(i == 0 || j == 0 || i == 15 || j == 15 ? 0.0 : 0.005);
      g.stiffness.push_back(300.0);
    }
  }
  const auto body = mat::MatBody::fit(g);
  std::vector<ModificationRow> rows;
  const std::array<double, 3> d{0.0, 0.0, -0.005};
  for (int pu = 1; pu <= 4; ++pu) {
    ModificationRow row{pu, pu, 0, 0, 0, 0};
    for (const auto& [u, v] : {std::pair{0.5, 0.5}, std::pair{0.4667, 0.4667}, std::pair{0.31, 0.62}}) {
      auto s = body.top();
      const auto before = body.top();
      const auto inf = deform::influence_at(s, u, v, pu, pu);
      deform::displace(s, inf, d, 0);
      {
        auto scratch = body.top();
        const auto start = Clock::now();
        for (int r = 0; r < 10000; ++r) {
          const auto again = deform::influence_at(scratch, u, v, pu, pu);
          deform::displace(scratch, again, d, 0);
        }
        row.ns = std::max(row.ns, std::chrono::duration<double, std::nano>(Clock::now() - start).count() / 1e4);
      }
      std::array<double, 3> a{};
      std::array<double, 3> b0{};
      s.evaluate(u, v, a);
      before.evaluate(u, v, b0);
      row.landing_error = std::max(row.landing_error, std::abs(a[2] - b0[2] - d[2]) / 0.005);
      for (int k = 0; k < inf.rows * inf.cols; ++k)
        row.max_control = std::max(row.max_control, inf.weight[static_cast<std::size_t>(k)]);
      for (int iu = 0; iu <= 200; ++iu) {
        for (int iv = 0; iv <= 200; ++iv) {
          s.evaluate(iu / 200.0, iv / 200.0, a);
          before.evaluate(iu / 200.0, iv / 200.0, b0);
          row.overshoot = std::max(row.overshoot, std::abs(a[2] - b0[2]) / 0.005);
        }
      }
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

int run_bench_dynamics(const std::filesystem::path& out_dir) {
  std::filesystem::create_directories(out_dir);
  const auto dyn = integrator_sweep();
  const auto mod = modification_sweep();

  std::ofstream csv(out_dir / "dynamics.csv");
  csv << "integrator,dt_s,max_error_m,ns_per_point_step,stable\n";
  std::printf("%-20s %8s %14s %12s %7s\n", "integrator", "dt s", "max error m", "ns/point", "stable");
  for (const auto& r : dyn) {
    csv << fmt::format("{},{:.0e},{:.3e},{:.1f},{}\n", r.integrator, r.dt, r.max_error, r.ns_per_step,
                       r.stable ? 1 : 0);
    std::printf("%-20s %8.0e %14.3e %12.1f %7s\n", r.integrator.c_str(), r.dt, r.max_error, r.ns_per_step,
                r.stable ? "yes" : "NO");
  }
  std::ofstream mcsv(out_dir / "modification.csv");
  mcsv << "p_prime,q_prime,landing_error_rel,max_dp_over_d,overshoot,ns_per_modification\n";
  std::printf("\n%6s %6s %16s %14s %10s %8s\n", "p'", "q'", "landing error", "max|dP|/|D|", "overshoot", "ns");
  for (const auto& r : mod) {
    mcsv << fmt::format("{},{},{:.3e},{:.4f},{:.4f},{:.0f}\n", r.pu, r.pv, r.landing_error, r.max_control, r.overshoot,
                        r.ns);
    std::printf("%6d %6d %16.3e %14.4f %10.4f %8.0f\n", r.pu, r.pv, r.landing_error, r.max_control, r.overshoot, r.ns);
  }

  plot::LinePlot p;
  p.title = "Spring integrators: max error over 0.2 s vs time step";
  p.x = {"time step dt (s)", plot::Scale::Log10, {}, {}};
  p.y = {"max |x - x_exact| (m); x0 1 mm, 300 N/m, 1 g, zeta 0.2", plot::Scale::Log10, 1e-18, 1e3};
  for (const auto& integ : kIntegrators) {
    plot::Series s{integ.name, {}, {}, plot::Marker::Circle, true};
    for (const auto& r : dyn) {
      if (r.integrator != integ.name) continue;
      s.x.push_back(r.dt);
      s.y.push_back(std::clamp(r.max_error, 1e-18, 1e3));  // unstable runs pinned at the top
    }
    p.series.push_back(s);
  }
  plot::save_png(p, out_dir / "dynamics.png");
  std::printf("\nwrote %s, %s, %s\n", (out_dir / "dynamics.csv").c_str(), (out_dir / "modification.csv").c_str(),
              (out_dir / "dynamics.png").c_str());
  return 0;
}

}  // namespace palpa::cli
