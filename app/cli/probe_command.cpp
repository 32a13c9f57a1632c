// palpa-cli probe CASE --points PTS.csv: foot point, penetration and force for each
// probe position, on the bodies at rest (paper sections 3.1 and 3.4).
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "palpa/options/number_checks.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/csv.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::cli {
namespace {

struct ProbeCommandOptions {
  std::string case_path;
  std::string points_path;
  bool no_shear = false;
  bool path = false;
  std::string method = "fast";
  int bisect_levels = 10;
  double max_force = contact::ForceOptions{}.max_force;
  double shear_delta = contact::ForceOptions{}.shear_delta;
};

int run_probe(const ProbeCommandOptions& o) {
  std::unique_ptr<scene::Scene> scene;
  try {
    const auto file = io::load_case(o.case_path);
    scene = std::make_unique<scene::Scene>(scene::Scene::build(file, o.case_path));
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }
  io::NumericTable points;
  try {
    points = io::read_numeric_csv(o.points_path, {"x", "y", "z"});
  } catch (const io::CsvError& e) {
    print_error(e.what());
    return kBadInput;
  }

  scene::ProbeOptions options;
  options.method = o.method == "bisect" ? scene::FootPointMethod::Bisect : scene::FootPointMethod::Fast;
  options.bisect_levels = o.bisect_levels;
  options.force.shear = !o.no_shear;
  options.force.max_force = o.max_force;
  options.force.shear_delta = o.shear_delta;
  options.remember_side = o.path;
  auto state = scene->make_state();

  std::printf("x,y,z,inside,body,u,v,depth,fx,fy,fz\n");
  for (const auto& p : points.rows) {
    const palpa::Vec3 q(p[0], p[1], p[2]);
    const auto r = scene->probe(q, state, options);
    std::printf("%.17g,%.17g,%.17g,%d,%s,", p[0], p[1], p[2], r.body >= 0 ? 1 : 0,
                r.body >= 0 ? scene->body(static_cast<std::size_t>(r.body)).body.id().c_str() : "");
    if (r.nearest >= 0) {
      std::printf("%.17g,%.17g,%.17g,", r.contact.foot.u, r.contact.foot.v, r.contact.depth);
    } else {
      std::printf(",,,");  // every body was culled: no foot point was searched
    }
    std::printf("%.17g,%.17g,%.17g\n", r.force.total.x(), r.force.total.y(), r.force.total.z());
  }
  return kOk;
}

}  // namespace

Command add_probe_command(CLI::App& parent) {
  auto o = std::make_shared<ProbeCommandOptions>();
  auto* app = parent.add_subcommand(
      "probe", "Foot point, penetration depth and contact force for each probe position, on the bodies at rest. "
               "CSV on stdout: x,y,z,inside,body,u,v,depth,fx,fy,fz (m, N; force on the probe; u, v, depth of the "
               "nearest body searched, empty when every body was culled).");
  app->add_option("CASE", o->case_path, "case file (JSON)")->required();
  app->add_option("--points", o->points_path, "CSV with header 'x,y,z' (m), one probe position per row")->required();
  app->add_flag("--no-shear", o->no_shear, "leave out the four shear springs (normal spring and tumours only)");
  app->add_flag("--path", o->path,
                "treat the rows as one continuous probe path: a press that goes past the skeleton keeps being pushed "
                "back out of the side it entered (without it, every row is an independent query)");
  app->add_option("--method", o->method, "foot-point search: fast (safeguarded Newton) or bisect (the paper's)")
      ->check(CLI::IsMember({"fast", "bisect"}))
      ->default_str("fast");
  app->add_option("--bisect-levels", o->bisect_levels, "levels k of the bisection (interval 2^-k); default 10")
      ->check(options::integer_in(1, 40));
  app->add_option("--max-force", o->max_force, "cap on |F| in N; default 30")->check(options::finite_positive(1000.0, "N"));
  app->add_option("--shear-delta", o->shear_delta, "parameter offset of the shear springs; default 0.1")
      ->check(options::finite_in(1e-6, 0.5));
  return {app, [o] { return run_probe(*o); }};
}

}  // namespace palpa::cli
