// palpa-cli bench import: the anatomy import's run time beside its fit error, as the
// paper's Table 1 puts time beside accuracy (docs/anatomy-import.md, BENCHMARKS.md).
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "bench_suites.hpp"
#include "commands.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"
#include "palpa/anatomy_io/anatomy_io.hpp"
#include "palpa/anatomy_io/import_request.hpp"

namespace palpa::cli {
namespace {

using Clock = std::chrono::steady_clock;

// A cap of a 150 mm sphere standing 60 mm high (120 mm in radius at its base) on a 10 mm
// support, with two masses: the body of a 256^3 volume of 1 mm voxels.
double cap_top(double x, double y) {
  const double q = 0.150 * 0.150 - x * x - y * y;
  return q > 0.0 ? -0.090 + std::sqrt(q) : -1.0;
}

int cap_label(const Vec3& p) {
  if ((p - Vec3(0.03, -0.02, 0.03)).norm() < 0.008 || (p - Vec3(-0.04, 0.035, 0.025)).norm() < 0.006) return 4;
  if (p.z() < 0.0) return p.z() > -0.010 ? 3 : 0;
  return p.z() < cap_top(p.x(), p.y()) ? 1 : 0;
}

anatomy::LabelVolume cap_volume(int n, double voxel) {
  anatomy::LabelVolume v;
  v.dims = {n, n, n};
  v.spacing = {voxel, voxel, voxel};
  v.origin = {-0.5 * voxel * (n - 1), -0.5 * voxel * (n - 1), -0.020};
  v.labels.resize(v.voxel_count());
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) v.labels[v.index(i, j, k)] = static_cast<std::uint16_t>(cap_label(to_vec3(v.world(i, j, k))));
    }
  }
  return v;
}

// The cap's skin, or its support plane, as a height-field mesh of 2 (n - 1)^2 triangles.
anatomy::TriangleMesh cap_mesh(int n, bool skin) {
  anatomy::TriangleMesh mesh;
  const double half = 0.128, step = 2.0 * half / (n - 1);
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const double x = -half + a * step, y = -half + b * step;
      mesh.points.push_back({x, y, skin ? std::max(cap_top(x, y), 0.0) : 0.0});
    }
  }
  for (int b = 0; b + 1 < n; ++b) {
    for (int a = 0; a + 1 < n; ++a) {
      const auto id = [n](int x, int y) { return static_cast<std::int32_t>(x + n * y); };
      mesh.triangles.push_back({id(a, b), id(a + 1, b), id(a + 1, b + 1)});
      mesh.triangles.push_back({id(a, b), id(a + 1, b + 1), id(a, b + 1)});
    }
  }
  return mesh;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

struct Row {
  std::string what;
  std::string grid;
  double seconds = 0.0, top_max = 0.0, top_rms = 0.0, bottom_max = 0.0, peak_mb = 0.0;
};

Row timed_import(const std::string& what, const anatomy_io::ImportRequest& request) {
  const auto start = Clock::now();
  const auto imported = anatomy_io::import_anatomy(request);
  const auto& f = imported.result.body.report;
  return {what, fmt::format("{}x{}", imported.result.body.grid.rows, imported.result.body.grid.cols), seconds(start),
          f.top.interior_max, f.top.interior_rms, f.bottom.interior_max, peak_rss_mb()};
}

std::vector<Row> grid_sweep(const anatomy::SurfacePair& pair) {
  std::vector<Row> rows;
  for (const auto& [r, c] : std::vector<std::pair<int, int>>{{9, 11}, {13, 15}, {17, 17}, {25, 25}, {33, 33}, {49, 49}, {65, 65}}) {
    const auto start = Clock::now();
    const auto fitted = anatomy::fit_body(pair, r, c, "body");
    rows.push_back({"fit of the 256^3 cap", fmt::format("{}x{}", r, c), seconds(start), fitted.report.top.interior_max,
                    fitted.report.top.interior_rms, fitted.report.bottom.interior_max, peak_rss_mb()});
  }
  return rows;
}

}  // namespace

int run_bench_import(const std::filesystem::path& out_dir, int voxels, int mesh_points) {
  try {
    std::filesystem::create_directories(out_dir);
    const auto volume_path = out_dir / "cap.nii.gz";
    anatomy_io::write_label_volume(volume_path, cap_volume(voxels, 256e-3 / voxels));
    const auto skin_path = out_dir / "cap-skin.stl", support_path = out_dir / "cap-support.stl";
    anatomy_io::write_mesh(skin_path, cap_mesh(mesh_points, true));
    anatomy_io::write_mesh(support_path, cap_mesh(mesh_points, false));
    std::vector<Row> rows;
    anatomy_io::ImportRequest volume;
    volume.input = volume_path;
    volume.labels = "generic";
    rows.push_back(timed_import(fmt::format("{}^3 label volume (.nii.gz) to a case", voxels), volume));
    anatomy_io::ImportRequest meshes;
    meshes.input = skin_path;
    meshes.support = support_path;
    meshes.modulus = 3240.0;
    rows.push_back(timed_import(fmt::format("two {}-triangle STL surfaces to a case", 2 * (mesh_points - 1) * (mesh_points - 1)), meshes));
    const auto pair = anatomy::surfaces_from_volume(anatomy_io::read_label_volume(volume_path),
                                                    anatomy::builtin_label_table("generic"), "cap.nii.gz");
    for (const Row& r : grid_sweep(pair)) rows.push_back(r);
    std::ofstream csv(out_dir / "import.csv");
    csv << "what,grid,seconds,top_interior_max_mm,top_interior_rms_mm,bottom_interior_max_mm,peak_rss_mb\n";
    std::printf("%-44s %7s %8s %10s %10s %10s %9s\n", "what", "grid", "time s", "top max", "top rms", "bottom max", "peak MB");
    for (const Row& r : rows) {
      csv << fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f}\n", r.what, r.grid, r.seconds, r.top_max * 1e3,
                         r.top_rms * 1e3, r.bottom_max * 1e3, r.peak_mb);
      std::printf("%-44s %7s %8.2f %7.3f mm %7.3f mm %7.3f mm %9.0f\n", r.what.c_str(), r.grid.c_str(), r.seconds,
                  r.top_max * 1e3, r.top_rms * 1e3, r.bottom_max * 1e3, r.peak_mb);
    }
    return kOk;
  } catch (const anatomy::ImportError& e) {
    print_error(e.what());
    return kFailure;
  }
}

}  // namespace palpa::cli
