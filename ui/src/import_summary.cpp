// The Import anatomy dialog's summary: what palpa-cli import prints, in the instructor's
// words (mm and kPa; tumours counted from 1).
#include <algorithm>

#include <fmt/format.h>

#include "import_preview.hpp"
#include "palpa/anatomy/surfaces.hpp"

namespace palpa::ui {
namespace {

std::string surface_line(const char* what, const anatomy::SurfaceError& e, double band) {
  return fmt::format("  {}: max {:.2f} mm, rms {:.2f} mm\n    away from the rim ({:.1f} mm): max {:.2f} mm, rms {:.2f} mm\n"
                     "    worst at {}\n",
                     what, e.max * 1e3, e.rms * 1e3, band * 1e3, e.interior_max * 1e3, e.interior_rms * 1e3,
                     anatomy::millimetres(e.worst));
}

std::string tissue_line(const mat::BodyGrid& body) {
  if (body.modulus.empty()) return {};
  const auto [lo, hi] = std::minmax_element(body.modulus.begin(), body.modulus.end());
  if (*hi - *lo <= 1e-6 * *hi) return fmt::format("Tissue: {:.2f} kPa\n", *lo / 1e3);
  return fmt::format("Tissue: {:.2f} to {:.2f} kPa\n", *lo / 1e3, *hi / 1e3);
}

std::string lesion_lines(const anatomy::ImportResult& r) {
  std::string kept, skipped;
  int n = 0;
  for (const anatomy::Lesion& l : r.lesions) {
    if (l.kept) {
      kept += fmt::format("  {}. {} (label {}) at {}, radius {:.1f} mm, {:.1f} kPa\n", ++n, l.name, l.label,
                          anatomy::millimetres(l.centre), l.radius * 1e3, l.modulus / 1e3);
    } else {
      skipped += fmt::format("  {} (label {}) at {}: {}\n", l.name, l.label, anatomy::millimetres(l.centre), l.skipped);
    }
  }
  std::string out = fmt::format("Tumours: {}\n{}", r.tumours.size(), kept);
  if (!skipped.empty()) out += "Skipped lesions (drawn faint):\n" + skipped;
  return out;
}

}  // namespace

QString import_summary(const anatomy_io::ImportedCase& imported) {
  const anatomy::ImportResult& r = imported.result;
  const anatomy::FitReport& f = r.body.report;
  const double spacing = r.body.s_sites.size() > 1 && r.body.t_sites.size() > 1
                             ? std::max(r.body.s_sites[1] - r.body.s_sites[0], r.body.t_sites[1] - r.body.t_sites[0])
                             : 0.0;
  std::string text = fmt::format("Grid: {} x {} skeleton points, {:.1f} mm apart\n", r.body.grid.rows, r.body.grid.cols,
                                 spacing * 1e3);
  text += fmt::format("Support: {}\n", std::string(r.surfaces.support_kind) == "curved" ? "curved" : "flat");
  text += fmt::format("Fit error, fitted body to the input (input resolution {:.2f} mm):\n", r.surfaces.resolution * 1e3);
  text += surface_line("top (skin)", f.top, f.rim_band);
  text += surface_line("bottom (support)", f.bottom, f.rim_band);
  if (!imported.file.bodies.empty()) text += tissue_line(imported.file.bodies.front());
  text += lesion_lines(r);
  text += fmt::format("Time: {:.2f} s (reading {:.2f} s, fitting {:.2f} s)\n", imported.read_seconds + r.seconds,
                      imported.read_seconds, r.seconds);
  return QString::fromStdString(text);
}

}  // namespace palpa::ui
