// palpa-cli import: segmented anatomy (a label volume, a skin mesh on a support mesh, or a
// closed mesh on a support plane) to a case; prints the fit error, the grid, the tumours
// and the time (docs/anatomy-import.md).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "output_guard.hpp"
#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"
#include "palpa/anatomy_io/import_request.hpp"
#include "palpa/report/printable.hpp"

namespace palpa::cli {
namespace {

struct ImportCommandOptions {
  std::string input, labels, support, support_plane, grid, exam_region = "free-surface", title, out, units = "mm";
  double modulus = 0.0;
  bool force = false;
};

std::string shown(const std::string& text) { return report::printable(text, 200); }

// "RxC" with 5 <= R, C <= 256 (no <regex>: GCC's, at -O1 with the sanitizers, warns inside itself).
bool parse_grid(const std::string& text, int& rows, int& cols) {
  const std::size_t x = text.find_first_of("xX");
  const auto number = [](const std::string& digits, int& out) {
    if (digits.empty() || digits.size() > 3 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stoi(digits);
    return true;
  };
  if (x == std::string::npos || !number(text.substr(0, x), rows) || !number(text.substr(x + 1), cols)) return false;
  return rows >= 5 && cols >= 5 && rows <= 256 && cols <= 256;
}

bool parse_plane(const std::string& text, std::array<double, 4>& plane) {
  std::size_t at = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t comma = text.find(',', at);
    if ((k < 3) == (comma == std::string::npos)) return false;
    const std::string part = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    try {
      std::size_t used = 0;
      plane[static_cast<std::size_t>(k)] = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(plane[static_cast<std::size_t>(k)])) return false;
    } catch (const std::exception&) {
      return false;
    }
    at = comma + 1;
  }
  return true;
}

// The request from the options; an empty string when they are consistent, else why not.
std::string build_request(const ImportCommandOptions& o, anatomy_io::ImportRequest& r) {
  r.input = o.input;
  r.labels = o.labels;
  r.support = o.support;
  r.modulus = o.modulus;
  r.title = o.title;
  r.metres_per_unit = o.units == "m" ? 1.0 : 1e-3;
  r.region = o.exam_region == "whole" ? anatomy::ExamRegion::Whole : anatomy::ExamRegion::FreeSurface;
  if (!o.grid.empty() && !parse_grid(o.grid, r.rows, r.cols)) {
    return fmt::format("--grid: \"{}\" is not RxC with 5 to 256 points each way (e.g. 33x41)", shown(o.grid));
  }
  if (!o.support_plane.empty()) {
    std::array<double, 4> plane{};
    if (!parse_plane(o.support_plane, plane)) {
      return fmt::format("--support-plane: \"{}\" is not four numbers \"nx,ny,nz,d\"", shown(o.support_plane));
    }
    r.support_plane = plane;
  }
  std::string command;
  if (!o.labels.empty()) command += " --labels " + o.labels;
  if (!o.support.empty()) command += " --support " + std::filesystem::path(o.support).filename().string();
  if (!o.support_plane.empty()) command += " --support-plane \"" + o.support_plane + "\"";
  if (o.modulus > 0.0) command += fmt::format(" --modulus {:g}", o.modulus);
  if (!o.grid.empty()) command += " --grid " + o.grid;
  command += " --exam-region " + o.exam_region;
  if (o.units != "mm") command += " --units " + o.units;
  r.command = command.substr(1);
  return {};
}

void print_surface(const char* what, const anatomy::SurfaceError& e, double band) {
  std::printf("          %s: max %.2f mm, rms %.2f mm; away from the rim (%.1f mm) max %.2f mm, rms %.2f mm; worst at %s\n",
              what, e.max * 1e3, e.rms * 1e3, band * 1e3, e.interior_max * 1e3, e.interior_rms * 1e3,
              anatomy::millimetres(e.worst).c_str());
}

void print_tissue(const mat::BodyGrid& body) {
  const auto [lo, hi] = std::minmax_element(body.modulus.begin(), body.modulus.end());
  std::printf("tissue    %.2f to %.2f kPa over the skeleton points, Poisson's ratio %.2f, stiffening %.2f\n", *lo / 1e3,
              *hi / 1e3, body.poisson, body.stiffening);
}

void print_lesions(const anatomy::ImportResult& r) {
  std::printf("tumours   %zu\n", r.tumours.size());
  for (const anatomy::Lesion& l : r.lesions) {
    if (l.kept) {
      std::printf("          %s (label %d) at %s, radius %.1f mm, %.1f kPa\n", shown(l.name).c_str(), l.label,
                  anatomy::millimetres(l.centre).c_str(), l.radius * 1e3, l.modulus / 1e3);
    } else {
      std::printf("skipped   %s (label %d) at %s: %s\n", shown(l.name).c_str(), l.label,
                  anatomy::millimetres(l.centre).c_str(), l.skipped.c_str());
    }
  }
}

void print_report(const ImportCommandOptions& o, const anatomy_io::ImportedCase& c) {
  const auto& r = c.result;
  const auto& f = r.body.report;
  std::printf("imported  %s\n", shown(std::filesystem::path(o.input).filename().string()).c_str());
  std::printf("support   %s (normal %.3f, %.3f, %.3f)\n", r.surfaces.support_kind, r.surfaces.frame.n.x(),
              r.surfaces.frame.n.y(), r.surfaces.frame.n.z());
  std::printf("grid      %d x %d skeleton points, %.1f mm apart\n", r.body.grid.rows, r.body.grid.cols,
              std::max(r.body.s_sites[1] - r.body.s_sites[0], r.body.t_sites[1] - r.body.t_sites[0]) * 1e3);
  std::printf("fit error from the fitted contours to the input surfaces (input resolution %.2f mm):\n",
              r.surfaces.resolution * 1e3);
  print_surface("top (skin)", f.top, f.rim_band);
  print_surface("bottom (support)", f.bottom, f.rim_band);
  print_tissue(c.file.bodies.front());
  print_lesions(r);
  for (const auto& note : r.notes) std::printf("note      %s\n", shown(note).c_str());
  std::printf("wrote     %s\n", shown(o.out).c_str());
  std::printf("time      %.2f s (reading %.2f s, fitting %.2f s)\n", c.read_seconds + r.seconds, c.read_seconds, r.seconds);
}

int run_import(const ImportCommandOptions& o) {
  anatomy_io::ImportRequest request;
  if (const std::string why = build_request(o, request); !why.empty()) {
    print_error(why);
    return kBadInput;
  }
  if (const std::string why = refusal_to_write(o.out, o.force, {o.input, o.support, o.labels}); !why.empty()) {
    print_error(why);
    return kBadInput;
  }
  anatomy_io::ImportedCase imported;
  try {
    imported = anatomy_io::import_anatomy(request);
  } catch (const anatomy::ImportError& e) {
    print_error(e.what());
    return kBadInput;
  }
  try {
    io::save_case(imported.file, o.out);
  } catch (const std::exception& e) {
    print_error(e.what());
    return kFailure;
  }
  print_report(o, imported);
  return kOk;
}

}  // namespace

Command add_import_command(CLI::App& parent) {
  auto o = std::make_shared<ImportCommandOptions>();
  auto* app = parent.add_subcommand(
      "import", "Make a case from segmented anatomy: a label volume (NIfTI, NRRD, MetaImage, VTI) with its label "
                "table, a skin mesh on a support mesh, or a closed mesh on a support plane (STL, OBJ, PLY); "
                "prints the fit error, the grid, the tumours and the time (docs/anatomy-import.md).");
  app->add_option("INPUT", o->input, "label volume, skin mesh or closed mesh")->required();
  app->add_option("--labels", o->labels, "a label volume's table: TABLE.json, victre or generic");
  app->add_option("--support", o->support, "the support mesh the skin mesh rests on (chest wall, pelvis, table)");
  app->add_option("--support-plane", o->support_plane,
                  "\"nx,ny,nz,d\": the plane nx x + ny y + nz z + d = 0 (d in the mesh's units) a closed mesh rests on");
  app->add_option("--modulus", o->modulus, "a mesh's tissue: Young's modulus in Pa (e.g. 3240)");
  app->add_option("--units", o->units, "a mesh's coordinates: mm (the default; 3D Slicer's) or m")
      ->check(CLI::IsMember({"mm", "m"}));
  app->add_option("--grid", o->grid, "skeleton points RxC (default: chosen from the body's size and curvature)");
  app->add_option("--exam-region", o->exam_region,
                  "free-surface (the default: where there is tissue) or whole (the whole top contour)")
      ->check(CLI::IsMember({"free-surface", "whole"}));
  app->add_option("--title", o->title, "the case's title (default: \"Imported from INPUT\")");
  app->add_option("--out", o->out, "the case file to write (JSON)")->required();
  app->add_flag("--force", o->force, "replace --out if it exists");
  return {app, [o] { return run_import(*o); }};
}

}  // namespace palpa::cli
