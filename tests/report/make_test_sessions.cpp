// Writes small session files with known content for the score and batch CLI tests:
//   make_test_sessions OUT_DIR CASE_JSON
// The case (data/cases/flat-5x5.json: the plane z = 0 over [-50, 50]^2 mm, radius
// r = 0.02 (1 - a^2)(1 - b^2), u = (x + 0.05) / 0.1, v = (y + 0.05) / 0.1) gets one tumour of
// radius 6 mm at (10, 10, 0) mm. Sessions (trainee, start, content):
//   OUT/alice-0.palpa    alice  2026-11-19T09:00:00Z  half the body, light, one mark far from the tumour
//   OUT/alice-1.palpa    alice  2026-11-20T10:00:00Z  the whole body in 10 mm strips, deep, a mark on the tumour
//   OUT/alice-2.palpa    alice  2026-11-21T08:00:00Z  like alice-1 but cut short (no End event)
//   OUT/sub/bob-1.palpa  "Bob O'Neil/<x>"  2026-11-20T12:00:00Z  whole body, mark on the tumour + one false mark
//   OUT/corrupt.palpa    not a session (text)
//   OUT/truncated.palpa  the first half of alice-1's bytes
//   OUT/notes.txt        not a .palpa file (folders are searched for *.palpa only)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "palpa/session/session_writer.hpp"

namespace fs = std::filesystem;
using palpa::session::Event;
using palpa::session::EventKind;

namespace {

constexpr double kRate = 250.0;  // Hz: enough for the scorer, small files
constexpr double kSpeed = 0.05;  // m/s along the path

double radius_at(double x, double y) {
  const double a = x / 0.05, b = y / 0.05;
  return 0.02 * (1 - a * a) * (1 - b * b);
}

/// A probe pressed `fraction` of the local thickness (2 r) into the top of the body at (x, y).
palpa::engine::Sample sample_at(double t, double x, double y, double fraction) {
  palpa::engine::Sample s;
  s.t = t;
  const double r = radius_at(x, y);
  const double depth = fraction * 2.0 * r;
  s.position = {x, y, r - depth};
  s.force = {0.0, 0.0, 200.0 * depth};
  s.body = 0;
  s.u = (x + 0.05) / 0.1;
  s.v = (y + 0.05) / 0.1;
  s.depth = depth;
  return s;
}

/// Strips along x, `spacing` apart, over x in [-45, 45] mm and y in [y0, y1]; returns the end time.
double raster(palpa::session::Session& session, double y0, double y1, double spacing, double fraction) {
  double t = 0.0;
  const double dt = 1.0 / kRate, step = kSpeed * dt;
  bool forward = true;
  for (double y = y0; y <= y1 + 1e-9; y += spacing) {
    const double xa = forward ? -0.045 : 0.045, xb = forward ? 0.045 : -0.045;
    const int n = static_cast<int>(std::ceil(std::abs(xb - xa) / step));
    for (int k = 0; k <= n; ++k) {
      session.samples.push_back(sample_at(t, xa + (xb - xa) * k / n, y, fraction));
      t += dt;
    }
    forward = !forward;
  }
  return t;
}

palpa::session::Session make(const nlohmann::json& case_document, const std::string& id, const std::string& trainee,
                             const std::string& started_at) {
  palpa::session::Session s;
  s.info.id = id;
  s.info.trainee = trainee;
  s.info.device = "virtual";
  s.info.software_version = "0.1.0";
  s.info.started_at = started_at;
  s.info.rate_hz = kRate;
  s.info.case_source = "data/cases/flat-5x5.json";
  s.info.case_document = case_document;
  s.info.extra = {{"mode", "trainee"}};  // trainee exercises: they make learning curves
  return s;
}

void add_mark(palpa::session::Session& s, std::int64_t id, double t, double x, double y) {
  Event e;
  e.t = t;
  e.kind = EventKind::Mark;
  e.mark = id;
  e.position = {x, y, radius_at(x, y)};
  s.events.push_back(e);
}

void finish(palpa::session::Session& s, double t_end, bool complete) {
  s.events.insert(s.events.begin(), Event{0.0, EventKind::Start, -1, {}, {}});
  std::stable_sort(s.events.begin(), s.events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  if (complete) s.events.push_back(Event{t_end, EventKind::End, -1, {}, "done"});
}

void write(const fs::path& path, const palpa::session::Session& s) {
  fs::remove(path);
  palpa::session::write_session(path, s);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_test_sessions OUT_DIR CASE_JSON\n");
    return 2;
  }
  const fs::path out(argv[1]);
  fs::create_directories(out / "sub");
  std::ifstream in(argv[2]);
  std::stringstream text;
  text << in.rdbuf();
  auto doc = nlohmann::json::parse(text.str());
  doc["tumors"] = nlohmann::json::array(
      {{{"body", "flat"}, {"center", {0.01, 0.01, 0.0}}, {"radius", 0.006}, {"stiffness", 1500.0}}});

  auto a0 = make(doc, "a0a0a0a0a0a0a0a0", "alice", "2026-11-19T09:00:00Z");
  double t = raster(a0, -0.045, 0.0, 0.01, 0.1);
  add_mark(a0, 1, t / 2, -0.03, -0.03);
  finish(a0, t, true);
  write(out / "alice-0.palpa", a0);

  auto a1 = make(doc, "a1a1a1a1a1a1a1a1", "alice", "2026-11-20T10:00:00Z");
  t = raster(a1, -0.045, 0.045, 0.01, 0.6);
  add_mark(a1, 1, t * 0.7, 0.0105, 0.0098);
  finish(a1, t, true);
  write(out / "alice-1.palpa", a1);

  auto a2 = make(doc, "a2a2a2a2a2a2a2a2", "alice", "2026-11-21T08:00:00Z");
  t = raster(a2, -0.045, 0.045, 0.01, 0.6);
  add_mark(a2, 1, t * 0.7, 0.0105, 0.0098);
  finish(a2, t, false);
  write(out / "alice-2.palpa", a2);

  auto b1 = make(doc, "b1b1b1b1b1b1b1b1", "Bob O'Neil/<x>", "2026-11-20T12:00:00Z");
  t = raster(b1, -0.045, 0.045, 0.01, 0.6);
  add_mark(b1, 1, t * 0.5, 0.0095, 0.0102);
  add_mark(b1, 2, t * 0.6, -0.03, 0.03);
  finish(b1, t, true);
  write(out / "sub" / "bob-1.palpa", b1);

  std::ofstream(out / "corrupt.palpa") << "this is not a Palpa session\n";
  std::ofstream(out / "notes.txt") << "not a session\n";
  {
    std::ifstream good(out / "alice-1.palpa", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(good)), std::istreambuf_iterator<char>());
    std::ofstream(out / "truncated.palpa", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  return 0;
}
