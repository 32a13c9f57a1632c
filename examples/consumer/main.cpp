// palpa-consumer CASE.json: loads a case with Palpa's core, fits the medial-axis model of
// every body and prints what it found, in SI units:
//
//   palpa 0.1.0
//   case CASE.json: 1 bodies
//   body breast: 9 x 11 points; top at the centre (0.000000000, 0.000000000, 0.050000000) m
//
// "The centre" is the middle grid point (rows / 2, cols / 2); the top contour there lies one
// radius above the skeleton along its normal.
#include <array>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/version.hpp"

int main(int argc, char** argv) {
  if (argc > 2) {
    std::fprintf(stderr, "usage: palpa-consumer [CASE.json]\n");
    return 2;
  }
  const std::string path = argc == 2 ? argv[1] : PALPA_CASES_DIR "/default.json";
  try {
    const palpa::io::CaseFile file = palpa::io::load_case(path);
    std::vector<palpa::mat::MatBody> bodies;
    for (const auto& grid : file.bodies) bodies.push_back(palpa::mat::MatBody::fit(grid));

    std::printf("palpa %s\n", palpa::kVersion);
    std::printf("case %s: %zu bodies\n", path.c_str(), bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const auto& body = bodies[b];
      const auto& grid = file.bodies[b];
      const double u = body.u_params()[static_cast<std::size_t>(grid.rows / 2)];
      const double v = body.v_params()[static_cast<std::size_t>(grid.cols / 2)];
      std::array<double, 3> top{};
      body.top().evaluate(u, v, top);
      std::printf("body %s: %d x %d points; top at the centre (%.9f, %.9f, %.9f) m\n", body.id().c_str(), grid.rows,
                  grid.cols, top[0], top[1], top[2]);
    }
    return 0;
  } catch (const palpa::io::CaseError& e) {
    for (const auto& line : e.lines()) std::fprintf(stderr, "%s\n", line.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
    return 1;
  }
}
