// palpa-cli fit CASE: fits a body's skeleton and contours; prints a summary or, with
// --eval, the surface at the (u, v) pairs of a CSV file.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/csv.hpp"
#include "palpa/mat/fit_residual.hpp"
#include "palpa/mat/mat_body.hpp"

namespace palpa::cli {
namespace {

struct FitCommandOptions {
  std::string case_path;
  std::string body_id;
  std::string surface = "skeleton";
  std::string eval_path;
  std::string parameterization = "chord";
};

std::string knot_list(const std::vector<double>& knots) {
  std::string s = "[";
  for (std::size_t i = 0; i < knots.size(); ++i) s += fmt::format("{}{:.6g}", i ? ", " : "", knots[i]);
  return s + "]";
}

int print_eval(const spline::BSplineSurface& surface, bool skeleton, const std::string& uv_path) {
  io::NumericTable uv;
  try {
    uv = io::read_numeric_csv(uv_path, {"u", "v"});
  } catch (const io::CsvError& e) {
    print_error(e.what());
    return kBadInput;
  }
  for (std::size_t r = 0; r < uv.rows.size(); ++r) {
    for (std::size_t c = 0; c < 2; ++c) {
      const double x = uv.rows[r][c];
      if (x < 0.0 || x > 1.0) {
        print_error(fmt::format("{}: line {}: {} = {:.17g} is outside [0, 1]", uv_path, uv.line_numbers[r],
                                uv.columns[c], x));
        return kBadInput;
      }
    }
  }
  std::printf(skeleton ? "u,v,x,y,z,radius,stiffness,damping,mass\n" : "u,v,x,y,z\n");
  std::vector<double> out(static_cast<std::size_t>(surface.dim()));
  for (const auto& row : uv.rows) {
    surface.evaluate(row[0], row[1], out);
    std::printf("%.17g,%.17g", row[0], row[1]);
    for (double x : out) std::printf(",%.17g", x);
    std::printf("\n");
  }
  return kOk;
}

void print_summary(const FitCommandOptions& o, const io::CaseFile& file, std::size_t index, const mat::MatBody& body,
                   double fit_ms) {
  const auto& grid = file.bodies[index];
  const auto& sk = body.skeleton();
  const auto res = mat::fit_residual(body, grid);
  std::printf("case      %s (\"%s\")\n", o.case_path.c_str(), file.title.c_str());
  std::printf("body      %s (%zu of %zu)\n", grid.id.c_str(), index + 1, file.bodies.size());
  std::printf("grid      %d x %d MAT points (rows along u x cols along v)\n", grid.rows, grid.cols);
  std::printf("degrees   p = %d (u), q = %d (v)\n", sk.degree_u(), sk.degree_v());
  std::printf("knots u   %s\n", knot_list(sk.knots_u()).c_str());
  std::printf("knots v   %s\n", knot_list(sk.knots_v()).c_str());
  std::printf("channels  skeleton: x y z radius stiffness damping mass%s; contours: x y z\n",
              grid.damping.empty() || grid.mass.empty() ? " (defaults filled in)" : "");
  std::printf("residual  at the data sites, max |S(u_i, v_j) - data|:\n");
  std::printf("          skeleton xyz %.3g m, radius %.3g m, stiffness %.3g N/m, damping %.3g N s/m, mass %.3g kg\n",
              std::max({res.skeleton[mat::kX], res.skeleton[mat::kY], res.skeleton[mat::kZ]}),
              res.skeleton[mat::kRadius], res.skeleton[mat::kStiffness], res.skeleton[mat::kDamping],
              res.skeleton[mat::kMass]);
  std::printf("          top contour %.3g m, bottom contour %.3g m\n", res.top, res.bottom);
  std::printf("memory    %zu bytes (skeleton, two contours, parameters)\n", body.memory_bytes());
  std::printf("time      %.3f ms to fit the skeleton and both contours\n", fit_ms);
}

int run_fit(const FitCommandOptions& o) {
  io::CaseFile file;
  try {
    file = io::load_case(o.case_path);
  } catch (const io::CaseError& e) {
    for (const auto& line : e.lines()) print_error(line);
    return kBadInput;
  }
  std::size_t index = 0;
  if (!o.body_id.empty()) {
    std::string ids;
    for (index = 0; index < file.bodies.size() && file.bodies[index].id != o.body_id; ++index) {
      ids += (ids.empty() ? "" : ", ") + file.bodies[index].id;
    }
    if (index == file.bodies.size()) {
      print_error(o.case_path + ": no body with id \"" + o.body_id + "\" (bodies: " + ids + ")");
      return kBadInput;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<mat::MatBody> body;
  try {
    mat::FitOptions fit_options;
    if (o.parameterization == "centripetal") {
      fit_options.interpolation.parameterization = spline::Parameterization::Centripetal;
    }
    body = std::make_unique<mat::MatBody>(mat::MatBody::fit(file.bodies[index], fit_options));
  } catch (const mat::FitError& e) {
    print_error(fmt::format("{}: /bodies/{}: cannot fit: {}", o.case_path, index, e.what()));
    return kBadInput;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  if (o.eval_path.empty()) {
    print_summary(o, file, index, *body, ms);
    return kOk;
  }
  const auto& surface = o.surface == "top" ? body->top() : o.surface == "bottom" ? body->bottom() : body->skeleton();
  return print_eval(surface, o.surface == "skeleton", o.eval_path);
}

}  // namespace

Command add_fit_command(CLI::App& parent) {
  auto o = std::make_shared<FitCommandOptions>();
  auto* app = parent.add_subcommand(
      "fit", "Fit a body's skeleton SK and its top and bottom contours (paper section 2.1); print a summary, "
             "or with --eval a CSV of the surface at given (u, v).");
  app->add_option("CASE", o->case_path, "case file (JSON)")->required();
  app->add_option("--body", o->body_id, "id of the body to fit (default: the first)");
  auto* eval = app->add_option("--eval", o->eval_path,
                                "CSV with header 'u,v' (values in [0,1]); prints 'u,v,x,y,z' (+ "
                                "'radius,stiffness,damping,mass' for the skeleton), one row per input row");
  app->add_option("--parameterization", o->parameterization,
                  "parameters of the data sites: chord (chord length, the default) or centripetal")
      ->check(CLI::IsMember({"chord", "centripetal"}))
      ->default_str("chord");
  app->add_option("--surface", o->surface, "surface to evaluate with --eval: skeleton, top or bottom")
      ->check(CLI::IsMember({"skeleton", "top", "bottom"}))
      ->default_str("skeleton")
      ->needs(eval);
  return {app, [o] { return run_fit(*o); }};
}

}  // namespace palpa::cli
