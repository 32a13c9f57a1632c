#include "frame_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <time.h>
#include <unistd.h>

#include <fmt/format.h>
#include <QApplication>
#include <QCheckBox>
#include <QEventLoop>
#include <QTimer>
#include <QWindow>

#include "palpa/scene/table1_scenes.hpp"
#include "palpa/live/live_exercise.hpp"
#include "palpa/ui/trainee_window.hpp"
#include "palpa/ui/vtk_view.hpp"

namespace palpa::gui {
namespace {

using Clock = std::chrono::steady_clock;

struct Row {
  int bodies = 0;
  int mat_points = 0;
  bool dynamics = false;
  bool zoomed = false;          // the camera on body 0 only (the others culled)
  int frames = 0;
  double fps_mean = 0.0;
  double fps_p5 = 0.0;          // 5th percentile of per-frame rates = 1 / p95 frame time
  double frame_p95_ms = 0.0;
  double tessellate_ms = 0.0;   // means per frame
  double upload_ms = 0.0;
  double render_ms = 0.0;
  double bodies_changed = 0.0;  // mean per frame
  double bodies_drawn = 0.0;    // mean per frame
  double triangles = 0.0;       // mean per frame, drawn
  double deviation_px = 0.0;    // after the last frame (TraineeWindow::drawn_deviation_px)
  double cpu_ms = 0.0;          // process CPU time per frame, all threads
  double haptic_hz = 0.0;
  unsigned long long ticks = 0;
  unsigned long long missed = 0;
};

// CPU time of the whole process (all threads: GUI, llvmpipe rasterizers, haptic, recorder).
double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Measure only once the view's native window is on screen: before that VTK's Render()
// returns at once and would count empty frames (seen on a loaded machine).
void wait_until_shown(ui::TraineeWindow& window) {
  const auto shown_by = Clock::now() + std::chrono::seconds(10);
  while (!window.view()->input()->isExposed() && Clock::now() < shown_by) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  if (!window.view()->input()->isExposed()) throw std::runtime_error("the view was not shown within 10 s");
}

// What the measured frames add up to.
struct FrameTotals {
  std::vector<double> periods;
  double tessellate = 0.0, upload = 0.0, render = 0.0, changed = 0.0, drawn = 0.0, triangles = 0.0;
  double cpu_used = 0.0;

  void add(double period, const ui::TraineeWindow::FrameTimes& f) {
    periods.push_back(period);
    tessellate += f.tessellate;
    upload += f.upload;
    render += f.render;
    changed += static_cast<double>(f.bodies_changed);
    drawn += static_cast<double>(f.bodies_drawn);
    triangles += static_cast<double>(f.triangles);
  }
};

// Drives the window's frames for `seconds` after a warm-up, the finger on the scene's script.
FrameTotals drive_frames(ui::TraineeWindow& window, const scene::Table1Scene& spec, double seconds) {
  FrameTotals totals;
  int warmup = 5;  // the first frames compile shaders and upload every body
  const auto begin = Clock::now();
  auto last = begin;
  auto measured_from = begin;
  double cpu_from = 0.0;
  QEventLoop loop;
  QTimer tick;
  // A zero timer fires whenever the event loop is idle, so Qt still composes and shows
  // every frame between two of them: the period is what a trainee would see.
  QObject::connect(&tick, &QTimer::timeout, [&] {
    const auto now = Clock::now();
    if (warmup == 0) {
      // The period since the last tick covers the frame drawn then (window.last_frame()).
      totals.add(std::chrono::duration<double>(now - last).count(), window.last_frame());
      if (now - measured_from >= std::chrono::duration<double>(seconds)) {
        totals.cpu_used = process_cpu_seconds() - cpu_from;
        loop.quit();
        return;
      }
    } else if (--warmup == 0) {
      measured_from = now;
      cpu_from = process_cpu_seconds();
    }
    last = now;
    const double t = std::chrono::duration<double>(now - begin).count();
    window.exercise().set_probe_target(scene::table1_probe(spec.bodies, t));
    window.frame();
  });
  tick.start(0);
  loop.exec();
  tick.stop();
  return totals;
}

void fill_frame_figures(const FrameTotals& totals, Row& row) {
  row.frames = static_cast<int>(totals.periods.size());
  if (totals.periods.empty()) return;
  double total = 0.0;
  for (double p : totals.periods) total += p;
  const double n = static_cast<double>(totals.periods.size());
  row.fps_mean = n / total;
  const double p95 = percentile(totals.periods, 0.95);
  row.frame_p95_ms = p95 * 1e3;
  row.fps_p5 = p95 > 0.0 ? 1.0 / p95 : 0.0;
  row.tessellate_ms = totals.tessellate / n * 1e3;
  row.upload_ms = totals.upload / n * 1e3;
  row.render_ms = totals.render / n * 1e3;
  row.bodies_changed = totals.changed / n;
  row.bodies_drawn = totals.drawn / n;
  row.triangles = totals.triangles / n;
  row.cpu_ms = totals.cpu_used / n * 1e3;
}

Row measure(const scene::Table1Scene& spec, bool dynamics, bool zoomed, const FrameBenchOptions& bench,
            const std::filesystem::path& dir) {
  live::LiveOptions options;
  options.trainee = "bench";
  options.mode = "bench";
  options.engine.dynamics = dynamics;
  options.session_path = dir / fmt::format("table1-{}{}.palpa", spec.bodies, dynamics ? "-dyn" : "-nodyn");
  std::filesystem::remove(options.session_path);
  auto exercise = std::make_unique<live::LiveExercise>(scene::make_table1_case(spec), "table1", options);
  ui::TraineeWindow window(std::move(exercise), QString("Table 1, %1 bodies").arg(spec.bodies));
  window.set_frame_interval(-1);  // this driver draws the frames, uncapped
  window.set_detail_pixels(bench.detail_px);
  if (zoomed) window.look_at_body(0);
  // The overlay off as a trainee turns it off: its checkbox.
  if (auto* box = window.findChild<QCheckBox*>("coverageOverlay"); box && !bench.overlay) box->setChecked(false);
  window.show();
  wait_until_shown(window);
  const FrameTotals totals = drive_frames(window, spec, bench.seconds);

  Row row;
  row.bodies = spec.bodies;
  row.mat_points = spec.mat_points;
  row.dynamics = dynamics;
  row.zoomed = zoomed;
  const auto& stats = window.exercise().loop_stats();
  row.ticks = stats.ticks();
  row.missed = stats.missed();
  row.haptic_hz = stats.mean_period() > 0.0 ? 1.0 / stats.mean_period() : 0.0;
  fill_frame_figures(totals, row);
  row.deviation_px = window.drawn_deviation_px();
  window.setProperty(ui::TraineeWindow::kCloseWithoutAsking, true);
  window.close();  // finishes the session; the file is only a by-product
  std::filesystem::remove(options.session_path);
  std::filesystem::remove(options.session_path.string() + "-wal");
  std::filesystem::remove(options.session_path.string() + "-shm");
  return row;
}

}  // namespace

int run_frame_bench(const FrameBenchOptions& options) {
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("palpa-bench-{}", ::getpid());
  std::filesystem::create_directories(dir);
  std::printf("palpa --bench: trainee window at its default size, coverage overlay %s, level of detail %s, haptic "
              "loop at 1 kHz, scripted finger pressing into the bodies, %.1f s per scene and mode\n",
              options.overlay ? "on" : "off",
              options.detail_px > 0.0 ? fmt::format("{:g} px", options.detail_px).c_str() : "off",
              options.seconds);
  std::printf("%6s %5s %5s %4s | %7s %8s %9s | %8s %8s %8s %7s %6s %7s %6s %6s | %8s %7s %7s\n", "bodies", "MAT",
              "dyn", "view", "fps", "fps p5", "p95 ms", "tess ms", "copy ms", "rend ms", "changed", "drawn", "cpu ms",
              "ktri", "dev px", "haptic", "missed", "ticks");
  std::vector<Row> rows;
  const auto& scenes = scene::table1_scenes();
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const auto& spec = scenes[k];
    if (options.max_bodies > 0 && spec.bodies > options.max_bodies) continue;
    // The largest scene also with the camera on one body: the culled bodies cost nothing.
    const bool largest = k + 1 == scenes.size() && spec.bodies > 1;
    for (const bool zoomed : {false, true}) {
      if (zoomed && !largest) continue;
      for (const bool dynamics : {true, false}) {
        const Row r = measure(spec, dynamics, zoomed, options, dir);
        std::printf(
            "%6d %5d %5s %4s | %7.1f %8.1f %9.2f | %8.2f %8.2f %8.2f %7.2f %6.1f %7.1f %6.1f %6.2f | %6.0f Hz %7llu %7llu\n",
            r.bodies, r.mat_points, r.dynamics ? "on" : "off", r.zoomed ? "one" : "all", r.fps_mean, r.fps_p5,
            r.frame_p95_ms, r.tessellate_ms, r.upload_ms, r.render_ms, r.bodies_changed, r.bodies_drawn, r.cpu_ms,
            r.triangles / 1e3, r.deviation_px, r.haptic_hz, r.missed, r.ticks);
        std::fflush(stdout);
        rows.push_back(r);
      }
    }
  }
  std::filesystem::remove_all(dir);
  std::printf("\nfps = frames / time; fps p5 = 1 / p95 frame time; tess/copy/rend = mean per frame of the snapshot "
              "+ re-tessellation, the copy into VTK, VTK's render (the rest of a frame is the buffer swap and the event loop); "
              "changed = bodies re-tessellated per frame; drawn = bodies in the camera's view (the others are culled: not re-tessellated, copied or drawn); view one = the camera on body 0 only; cpu ms = CPU time of all the process's threads per frame (what the "
              "frame costs whatever else runs); ktri = thousands of triangles drawn; dev px = the largest distance between a drawn "
              "triangle and its surface after the last frame, in pixels at the body's largest magnification; haptic = the loop's mean rate over the window's life.\n");
  if (options.csv) {
    std::ofstream out(*options.csv);
    out << "bodies,mat_points,dynamics,view,frames,fps_mean,fps_p5,frame_p95_ms,tessellate_ms,upload_ms,render_ms,"
           "bodies_changed_per_frame,bodies_drawn_per_frame,cpu_ms_per_frame,haptic_hz,haptic_missed,haptic_ticks,overlay,"
           "triangles_per_frame,deviation_px,detail_px\n";
    for (const auto& r : rows) {
      out << fmt::format("{},{},{},{},{},{:.2f},{:.2f},{:.3f},{:.3f},{:.3f},{:.3f},{:.2f},{:.2f},{:.3f},{:.1f},{},{},{},{:.0f},{:.3f},{:g}",
                         r.bodies, r.mat_points, r.dynamics ? 1 : 0, r.zoomed ? "one" : "all", r.frames, r.fps_mean,
                         r.fps_p5, r.frame_p95_ms, r.tessellate_ms, r.upload_ms, r.render_ms, r.bodies_changed,
                         r.bodies_drawn, r.cpu_ms, r.haptic_hz, r.missed, r.ticks, options.overlay ? 1 : 0,
                         r.triangles, r.deviation_px, options.detail_px)
          << "\n";
    }
    if (!out) {
      std::fprintf(stderr, "palpa: error: %s: cannot write\n", options.csv->c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace palpa::gui
