// Writes a small finished session (format 2) for the Python readability test
// (tests/cli/test_session_python.py): session_example OUT.palpa CASE.json
// Sample k: t = k / 1000, x = k / 8, y = -k / 16, z = 0.03, force (0, 0, k / 4), in
// contact with body 0 when k is odd (u = k / 1024, v = 0.5, depth = k / 65536).
// session_example --dump FILE.palpa prints the C++ reader's ticks, one per line: tick t x y
// z fx fy fz body u v depth buttons overrun fault, doubles in shortest round-trip form.
#include <cstdio>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "palpa/io/case_file.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"

namespace {

int dump(const char* path) {
  const auto s = palpa::session::read_session(path);
  for (std::size_t k = 0; k < s.samples.size(); ++k) {
    const auto& x = s.samples[k];
    std::string contact = "None None None None";
    if (x.body >= 0) contact = fmt::format("{} {} {} {}", x.body, x.u, x.v, x.depth);
    fmt::print("{} {} {} {} {} {} {} {} {} {} {} {}\n", k, x.t, x.position[0], x.position[1], x.position[2],
               x.force[0], x.force[1], x.force[2], contact, x.buttons, x.overrun ? 1 : 0, x.fault ? 1 : 0);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace palpa;
  if (argc == 3 && std::string(argv[1]) == "--dump") {
    try {
      return dump(argv[2]);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
  }
  if (argc != 3) {
    std::fprintf(stderr, "usage: session_example OUT.palpa CASE.json | session_example --dump FILE.palpa\n");
    return 2;
  }
  try {
    session::Session s;
    s.info.trainee = "python-reader";
    s.info.device = "virtual";
    s.info.software_version = "test";
    s.info.case_source = argv[2];
    s.info.case_document = io::to_json(io::load_case(argv[2]));
    s.info.seed = 42;
    s.info.extra = {{"style", "free"}};
    for (int k = 0; k < 100; ++k) {
      engine::Sample x;
      const double d = k;
      x.t = d / 1000.0;
      x.position = {d / 8.0, -d / 16.0, 0.03};
      x.force = {0.0, 0.0, d / 4.0};
      if (k % 2 == 1) {
        x.body = 0;
        x.u = d / 1024.0;
        x.v = 0.5;
        x.depth = d / 65536.0;
      }
      x.buttons = k == 50 ? 1u : 0u;
      s.samples.push_back(x);
    }
    const auto event = [&](double t, session::EventKind kind, std::int64_t mark, std::array<double, 3> at) {
      session::Event e;
      e.t = t;
      e.kind = kind;
      e.mark = mark;
      e.position = at;
      s.events.push_back(e);
    };
    event(0.0, session::EventKind::Start, -1, {});
    event(0.02, session::EventKind::Mark, 1, {0.01, 0.02, 0.03});
    event(0.03, session::EventKind::Mark, 2, {0.04, 0.05, 0.06});
    event(0.04, session::EventKind::Unmark, 1, {});
    event(0.099, session::EventKind::End, -1, {});
    session::write_session(argv[1], s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
