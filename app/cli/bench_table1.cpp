#include "bench_table1.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <atomic>
#include <thread>

#include <fmt/format.h>

#include "palpa/engine/drawn_scene.hpp"
#include "palpa/engine/engine.hpp"
#include "palpa/engine/realtime_loop.hpp"
#include "palpa/engine/virtual_device.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/scene/table1_scenes.hpp"

namespace palpa::cli {
namespace {

using Clock = std::chrono::steady_clock;

using scene::Table1Scene;

// The scripted palpation over the scene (scene::table1_probe) sampled at 200 Hz.
engine::Trajectory palpation(const Table1Scene& spec, double seconds) {
  engine::Trajectory tr;
  const int steps = static_cast<int>(seconds * 200.0);
  for (int k = 0; k <= steps; ++k) {
    const double t = k / 200.0;
    tr.t.push_back(t);
    tr.position.push_back(scene::table1_probe(spec.bodies, t));
  }
  return tr;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::min<double>(static_cast<double>(v.size() - 1), q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

struct StepTimes {
  double p50_us, p99_us, mean_us, max_us;  ///< the haptic tick: contact, force, governor
  double display_p50_us, display_p99_us, display_mean_us;  ///< the drawn bodies following it
  double serial_p99_us;  ///< both in one thread, as the paper's loop did
  int contact_ticks;
};

double micros(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::micro>(to - from).count();
}

// The ticks as the real-time loop runs them, unpaced: this thread ticks, a display thread
// follows every touch in order on the drawn bodies (as RealtimeLoop's does), each timed.
void time_beside(engine::Engine& eng, int ticks, std::vector<double>& tick_us, std::vector<double>& draw_us,
                 int& contacts) {
  auto ring = std::make_unique<engine::TouchRing>();
  std::atomic<bool> done{false};
  std::thread display([&] {
    engine::DrawnScene drawn(eng);
    engine::Touch touch;
    for (;;) {
      const bool last = done.load(std::memory_order_acquire);
      bool took = false;
      while (ring->try_pop(touch)) {
        const auto start = Clock::now();
        drawn.follow(touch);
        draw_us.push_back(micros(start, Clock::now()));
        took = true;
      }
      if (!took && last) break;
    }
  });
  for (int k = 0; k <= ticks; ++k) {
    const auto start = Clock::now();
    const auto s = eng.tick(k * 1e-3);
    tick_us.push_back(micros(start, Clock::now()));
    contacts += s.body >= 0 ? 1 : 0;
    while (!ring->try_push(eng.last_touch())) std::this_thread::yield();  // every touch is drawn and timed
  }
  done.store(true, std::memory_order_release);
  display.join();
}

// The paper's arrangement: tick and drawn bodies in one thread.
std::vector<double> time_serial(engine::Engine& eng, int ticks) {
  engine::DrawnScene drawn(eng);
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(ticks) + 1);
  for (int k = 0; k <= ticks; ++k) {
    const auto start = Clock::now();
    eng.tick(k * 1e-3);
    drawn.follow(eng.last_touch());
    us.push_back(micros(start, Clock::now()));
  }
  return us;
}

StepTimes time_ticks(const scene::Scene& scene, const engine::Trajectory& tr, bool dynamics, double display_span) {
  engine::EngineOptions options;
  options.dynamics = dynamics;
  options.deform.display_span = display_span;
  const auto ticks = static_cast<int>(tr.duration() * 1000.0);
  std::vector<double> tick_us, draw_us;
  tick_us.reserve(static_cast<std::size_t>(ticks) + 1);
  draw_us.reserve(static_cast<std::size_t>(ticks) + 1);
  int contacts = 0;
  {
    engine::ScriptedDevice device(tr);
    engine::Engine eng(scene, device, options);
    time_beside(eng, ticks, tick_us, draw_us, contacts);
  }
  engine::ScriptedDevice device(tr);
  engine::Engine eng(scene, device, options);
  const auto serial_us = time_serial(eng, ticks);
  return {percentile(tick_us, 0.5),  percentile(tick_us, 0.99), mean(tick_us),
          *std::max_element(tick_us.begin(), tick_us.end()),
          percentile(draw_us, 0.5),  percentile(draw_us, 0.99), mean(draw_us),
          percentile(serial_us, 0.99), contacts};
}

struct PacedRun {
  double rate_hz = 0.0;
  std::uint64_t ticks = 0;
  std::uint64_t missed = 0;
  double p99_period_us = 0.0;
  double max_period_us = 0.0;
  double p99_compute_us = 0.0;  ///< the tick's own time, as the loop measured it
  std::string scheduling;
};

// The scene on the real-time loop at 1 kHz for `seconds`, the probe palpating as above.
PacedRun paced_run(const scene::Scene& scene, const engine::Trajectory& tr, double seconds, double display_span) {
  engine::ScriptedDevice device(tr);
  engine::EngineOptions options;
  options.deform.display_span = display_span;
  engine::Engine eng(scene, device, options);
  auto loop_owner = std::make_unique<engine::RealtimeLoop>(eng);  // 1.6 MB of rings: not on the stack
  auto& loop = *loop_owner;
  PacedRun run;
  run.scheduling = loop.start();
  engine::Sample s;
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    while (loop.pop_sample(s)) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  loop.stop();
  while (loop.pop_sample(s)) {
  }
  const auto& st = loop.stats();
  run.ticks = st.ticks();
  run.missed = st.missed();
  run.rate_hz = st.mean_period() > 0.0 ? 1.0 / st.mean_period() : 0.0;
  run.p99_period_us = st.period_percentile(0.99) * 1e6;
  run.max_period_us = st.max_period() * 1e6;
  run.p99_compute_us = st.compute_percentile(0.99) * 1e6;
  return run;
}

// Busy threads on the other cores, to show the haptic thread holds its rate under load.
class CpuLoad {
 public:
  explicit CpuLoad(bool on) {
    if (!on) return;
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned k = 0; k < n; ++k) {
      threads_.emplace_back([this] {
        volatile double x = 1.0;
        while (!stop_.load(std::memory_order_relaxed)) x = x * 1.0000001 + 1e-9;
      });
    }
  }
  ~CpuLoad() {
    stop_.store(true);
    for (auto& t : threads_) t.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// Each body given by the Young's modulus whose derived stiffness (calibrated law, pad over
// the local thickness) is the stiffness it has: the same forces, the calibrated law's tick.
void in_pascal(io::CaseFile& file, bool finger) {
  for (auto& g : file.bodies) {
    const mat::LayerStiffnessTable layer(g.poisson, mat::kFingertipPadRadius);
    g.modulus.resize(g.stiffness.size());
    for (std::size_t k = 0; k < g.stiffness.size(); ++k) g.modulus[k] = g.stiffness[k] / layer(1.0, 2.0 * g.radius[k]);
    g.stiffness = mat::layer_stiffness_field(g.modulus, g.radius, g.poisson);
    g.force_model = mat::ForceModel::Calibrated;
  }
  file.indenter = finger ? mat::Indenter::Finger : mat::Indenter::Pad;
}

}  // namespace

int run_bench_table1(const Table1Options& options) {
  std::printf("Palpa on this machine against the paper's Table 1 (700 MHz Pentium III, 1 kHz haptic thread)\n\n");
  std::printf("%6s %6s | %10s %9s | %10s %10s %10s %10s | %9s %9s | %11s %11s %11s | %s\n", "bodies", "MAT",
              "preproc ms", "memory KB", "p50 us dyn", "p99 us dyn", "p50 nodyn", "p99 nodyn", "max Hz", "core %",
              "draw p99 dyn", "draw nodyn", "serial p99", "paper: preproc s, MB, Hz dyn/nodyn");
  std::vector<std::string> csv_rows;
  if (options.tissue_in_pa) {
    std::printf("Bodies given in kPa under the calibrated law%s.\n\n",
                options.finger ? ", pressed by the rounded finger" : " (the fingertip pad)");
  }
  for (const auto& spec : scene::table1_scenes()) {
    io::CaseFile file = scene::make_table1_case(spec);
    if (options.tissue_in_pa) in_pascal(file, options.finger);
    const auto start = Clock::now();
    const auto scene = scene::Scene::build(file, "table1");
    const double pre_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    std::size_t memory = 0;
    for (std::size_t b = 0; b < scene.size(); ++b) {
      const auto& sb = scene.body(b);
      memory += sb.body.memory_bytes() + static_cast<std::size_t>(sb.search.sample_count()) * (sizeof(double) * 5);
    }
    const auto tr = palpation(spec, options.seconds);
    const auto dyn = time_ticks(scene, tr, true, options.display_span);
    const auto nodyn = time_ticks(scene, tr, false, options.display_span);
    // The highest rate the worst 1 % of ticks still fits (one core, nothing else to do).
    const double max_rate = 1e6 / std::max(dyn.p99_us, nodyn.p99_us);
    const double core_share = dyn.mean_us * 1000.0 / 1e6 * 100.0;  // at 1 kHz, the haptic thread's
    PacedRun paced;
    if (options.realtime_seconds > 0.0) {
      const CpuLoad load(options.load);
      paced = paced_run(scene, palpation(spec, options.realtime_seconds + 1.0), options.realtime_seconds,
                        options.display_span);
      if (spec.bodies == 1 && spec.mat_points == 49) std::printf("%s%s\n", paced.scheduling.c_str(), options.load ? "; all cores loaded by busy threads" : "");
    }
    std::printf("%6d %6d | %10.2f %9.1f | %10.2f %10.2f %10.2f %10.2f | %9.0f %8.2f%% | %11.2f %11.2f %11.2f | %g s, "
                "%g MB, %g/%g Hz\n",
                spec.bodies, spec.mat_points, pre_ms, static_cast<double>(memory) / 1024.0, dyn.p50_us, dyn.p99_us,
                nodyn.p50_us, nodyn.p99_us, max_rate, core_share, dyn.display_p99_us, nodyn.display_p99_us,
                dyn.serial_p99_us, spec.paper_pre_s, spec.paper_mb, spec.paper_hz_dyn, spec.paper_hz_nodyn);
    if (options.realtime_seconds > 0.0) {
      std::printf("%6s %6s   paced at 1 kHz for %.0f s: %.1f Hz, %llu of %llu deadlines missed, period p99 %.0f us, max "
                  "%.0f us, tick p99 %.1f us\n",
                  "", "", options.realtime_seconds, paced.rate_hz, static_cast<unsigned long long>(paced.missed),
                  static_cast<unsigned long long>(paced.ticks), paced.p99_period_us, paced.max_period_us,
                  paced.p99_compute_us);
    }
    csv_rows.push_back(fmt::format(
        "{},{},{:.3f},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f},{:.3f},{},{:.2f},{},{},"
        "{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f}",
        spec.bodies, spec.mat_points, pre_ms, memory, dyn.p50_us, dyn.p99_us, nodyn.p50_us, nodyn.p99_us, max_rate,
        core_share, dyn.contact_ticks, paced.rate_hz, paced.missed, paced.ticks, dyn.display_p50_us, dyn.display_p99_us,
        nodyn.display_p50_us, nodyn.display_p99_us, dyn.serial_p99_us, nodyn.serial_p99_us, paced.p99_compute_us));
  }
  std::printf("\nStep times over %.0f s of palpation visiting every body. p50/p99 dyn and nodyn: one haptic tick "
              "(device read, foot point and force on the rest bodies, governor) while a display thread follows the "
              "touches, as on the real-time loop; max Hz = 1 / p99. draw: the drawn bodies following one touch (press, "
              "springs of the awake bodies) on that display thread; serial: tick and draw in one thread, as the "
              "paper's loop ran.\n",
              options.seconds);
  if (options.csv) {
    std::ofstream out(*options.csv);
    out << "bodies,mat_points,preprocess_ms,memory_bytes,step_p50_us_dyn,step_p99_us_dyn,step_p50_us_nodyn,"
           "step_p99_us_nodyn,max_rate_hz,core_share_percent_1khz,contact_ticks,rate_1khz_hz,missed_1khz,ticks_1khz,"
           "draw_p50_us_dyn,draw_p99_us_dyn,draw_p50_us_nodyn,draw_p99_us_nodyn,serial_p99_us_dyn,serial_p99_us_nodyn,"
           "tick_p99_us_1khz\n";
    for (const auto& r : csv_rows) out << r << "\n";
    if (!out) {
      std::fprintf(stderr, "palpa-cli: error: %s: cannot write\n", options.csv->c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace palpa::cli
