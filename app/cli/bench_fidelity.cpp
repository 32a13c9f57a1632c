#include "bench_fidelity.hpp"

#include "bench_fidelity_contrast.hpp"
#include "bench_fidelity_growth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "palpa/author/presets.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/plot/line_plot.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::cli {
namespace {

// The force-depth references: a frictionless 7.5 mm flat punch (or an 8 mm rounded finger)
// on a layer bonded to a rigid base, 60 mm in radius (data/reference/README.md). The 1x
// inclusion twins are plain layers meshed around an inclusion of the layer's own modulus.
struct Reference {
  const char* file;
  double thickness;  // m
  double modulus;    // Pa
  const char* what;
  bool plotted;      // in fidelity.png (the pinned and twin curves are in the CSV and the table)
  mat::Indenter indenter = mat::Indenter::Pad;
};

constexpr Reference kReferences[] = {
    {"slab40_E5k_flat_neohooke.csv", 0.040, 5000.0, "40 mm, neo-Hookean", true},
    {"slab40_E5k_flat_neohooke_pinned.csv", 0.040, 5000.0, "40 mm, neo-Hookean, edge pinned", false},
    {"slab40_E5k_flat_neohooke_pinned_incl1x.csv", 0.040, 5000.0, "40 mm, neo-Hookean, pinned, 1x twin", false},
    {"slab40_E5k_flat_linear.csv", 0.040, 5000.0, "40 mm, linear", true},
    {"slab40_E5k_flat_linear_incl1x.csv", 0.040, 5000.0, "40 mm, linear, 1x twin", false},
    {"slab40_E5k_flat_neohooke_pinned_r10d20_incl1x.csv", 0.040, 5000.0, "40 mm, neo-Hookean, pinned, 1x twin 2",
     false},
    {"slab20_E5k_flat_neohooke.csv", 0.020, 5000.0, "20 mm, neo-Hookean", true},
    {"slab20_E5k_flat_neohooke_pinned_incl1x.csv", 0.020, 5000.0, "20 mm, neo-Hookean, pinned, 1x twin", false},
    {"slab20_E5k_flat_neohooke_pinned.csv", 0.020, 5000.0, "20 mm, neo-Hookean, edge pinned", false},
    {"slab20_E5k_flat_linear.csv", 0.020, 5000.0, "20 mm, linear", true},
    {"slab30_E5k_flat_linear.csv", 0.030, 5000.0, "30 mm, linear", false},
    {"slab30_E5k_flat_neohooke_pinned.csv", 0.030, 5000.0, "30 mm, neo-Hookean, edge pinned", false},
    {"slab40_E5k_finger8_neohooke.csv", 0.040, 5000.0, "40 mm, neo-Hookean, 8 mm finger", true,
     mat::Indenter::Finger},
    {"slab40_E5k_finger8_neohooke_incl1x.csv", 0.040, 5000.0, "40 mm, neo-Hookean, 8 mm finger, 1x twin", false,
     mat::Indenter::Finger},
    {"slab20_E5k_finger8_neohooke.csv", 0.020, 5000.0, "20 mm, neo-Hookean, 8 mm finger", true,
     mat::Indenter::Finger},
};

constexpr double kSlabWidth = 0.12;  // m: the 60 mm-radius disc stands in for a 120 mm slab
constexpr double kTolerance = 0.10;  // the calibrated law's mark: within 10 % of the FEM
constexpr double kHalfWidthTolerance = 0.003;  // m: the lateral half-width's mark

struct Curve {
  std::vector<double> depth, force;  // m, N; without the 0,0 row
};

Curve read_curve(const std::filesystem::path& path) {
  Curve c;
  for (const auto& [d, f] : fidelity::read_force_curve(path)) {
    c.depth.push_back(d);
    c.force.push_back(f);
  }
  return c;
}

struct Row {
  const Reference* reference;
  mat::ForceModel law;
  Curve fem;
  std::vector<double> palpa;  // N, at fem.depth
  double worst = 0.0;         // largest |palpa / fem - 1|
};

Row compare(const Reference& r, const Curve& fem, mat::ForceModel law) {
  io::CaseFile file = author::make_modulus_slab(kSlabWidth, r.thickness, r.modulus, law);
  file.indenter = r.indenter;  // the paper's law has springs, not an indenter: it ignores this
  const auto scene = scene::Scene::build(file, r.file);
  Row row{&r, law, fem, {}, 0.0};
  for (std::size_t k = 0; k < fem.depth.size(); ++k) {
    row.palpa.push_back(fidelity::centre_force(scene, fem.depth[k]));
    if (fem.force[k] > 0.0) row.worst = std::max(row.worst, std::abs(row.palpa.back() / fem.force[k] - 1.0));
  }
  return row;
}

void write_csv(const std::vector<Row>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "reference,law,thickness_m,depth_m,depth_share,fem_n,palpa_n,error\n";
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.fem.depth.size(); ++k) {
      out << fmt::format("{},{},{:.3f},{:.6g},{:.4f},{:.6g},{:.6g},{:.5f}\n", r.reference->file, mat::to_string(r.law),
                         r.reference->thickness, r.fem.depth[k], r.fem.depth[k] / r.reference->thickness,
                         r.fem.force[k], r.palpa[k], r.palpa[k] / r.fem.force[k] - 1.0);
    }
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void write_png(const std::vector<Row>& rows, const std::filesystem::path& path) {
  plot::LinePlot p;
  p.title = "Force against the FEM: calibrated law (circles), paper's (squares)";
  p.x = {"depth / layer thickness", plot::Scale::Linear, 0.0, {}};
  p.y = {"Palpa / FEM - 1 (force)", plot::Scale::Linear, {}, {}};
  for (const auto& r : rows) {
    if (!r.reference->plotted) continue;  // the CSV has them all; ten curves stay readable
    const bool calibrated = r.law == mat::ForceModel::Calibrated;
    // The paper's springs against a finger are 6-9 times off at first touch: in the table.
    if (!calibrated && r.reference->indenter == mat::Indenter::Finger) continue;
    plot::Series s{std::string(r.reference->what) + (calibrated ? "" : ", paper"), {}, {},
                   calibrated ? plot::Marker::Circle : plot::Marker::Square, true};
    for (std::size_t k = 0; k < r.fem.depth.size(); ++k) {
      s.x.push_back(r.fem.depth[k] / r.reference->thickness);
      s.y.push_back(r.palpa[k] / r.fem.force[k] - 1.0);
    }
    p.series.push_back(std::move(s));
  }
  plot::save_png(p, path);
}


// The force curves: worst error per reference and law; true when the calibrated law meets
// the mark on every one.
bool print_forces(const std::vector<Row>& rows, const std::filesystem::path& reference_dir) {
  std::printf("Palpa on the finite-element reference layers (%s), pressed at the centre; the layer given in Pa.\n",
              reference_dir.c_str());
  std::printf("%-38s %9s | %22s | %22s\n", "reference", "reach", "calibrated: worst error", "paper's law: worst error");
  bool met = true;
  for (std::size_t k = 0; k + 1 < rows.size(); k += 2) {
    const auto& c = rows[k];
    const auto& p = rows[k + 1];
    const double reach = c.fem.depth.back();
    std::printf("%-38s %4.1f mm %2.0f%% | %21.1f%% | %21.1f%%\n", c.reference->what, reach * 1e3,
                100.0 * reach / c.reference->thickness, 100.0 * c.worst, 100.0 * p.worst);
    met = met && c.worst <= kTolerance;
  }
  return met;
}

std::string onset_text(double onset) {
  if (onset < 0.0) return "never";
  return fmt::format("{:.2f} mm", onset * 1e3);
}

std::string half_width_text(double width, double fem) {
  return fmt::format("{:.1f} mm ({:+.1f} mm)", width * 1e3, (width - fem) * 1e3);
}

// The on-axis contrast and onset table; true when the calibrated law meets both marks on
// every inclusion.
bool print_on_axis(const std::vector<fidelity::Inclusion>& rows) {
  std::printf("\nTumour contrast F_with / F_without on the pad's axis, layers of 5 kPa (contrast_slab*_E5k_linear.csv): "
              "the tumour in Pa at a 2 mm press in the small-strain limit the linear sweeps stand for (its growth with the "
              "press: next table); the paper's law with a tumour spring of 0.02 m x E_t at 4 mm. Onset: the first "
              "press with contrast >= 1.10 (up to 40 %% of the layer).\n");
  std::printf("%6s %7s %10s %5s | %7s %8s | %10s %7s %8s | %8s %7s %8s\n", "layer", "radius", "centre", "ratio", "FEM",
              "onset", "calibrated", "error", "onset", "paper's", "error", "onset");
  std::size_t contrast_ok = 0, onset_ok = 0, paper_contrast_ok = 0, paper_onset_ok = 0;
  for (const auto& r : rows) {
    const bool c_ok = fidelity::contrast_met(r.calibrated, r.fem);
    const bool o_ok = fidelity::onset_met(r.calibrated_onset, r.fem_onset);
    contrast_ok += c_ok;
    onset_ok += o_ok;
    paper_contrast_ok += fidelity::contrast_met(r.paper, r.fem);
    paper_onset_ok += fidelity::onset_met(r.paper_onset, r.fem_onset);
    std::printf("%3.0f mm %4.0f mm %5.0f mm deep %4gx | %7.4f %8s | %10.4f %+6.3f%s %8s%s | %8.4f %+7.3f %8s\n",
                r.thickness * 1e3, r.radius * 1e3, r.depth * 1e3, r.ratio, r.fem, onset_text(r.fem_onset).c_str(),
                r.calibrated, r.calibrated - r.fem, c_ok ? " " : "!", onset_text(r.calibrated_onset).c_str(),
                o_ok ? " " : "!", r.paper, r.paper - r.fem, onset_text(r.paper_onset).c_str());
  }
  std::printf("contrast within 20 %% of C - 1 or 0.02: calibrated %zu of %zu, paper's law %zu of %zu\n", contrast_ok,
              rows.size(), paper_contrast_ok, rows.size());
  std::printf("onset within 2 mm (or neither reaching 1.10): calibrated %zu of %zu, paper's law %zu of %zu\n", onset_ok,
              rows.size(), paper_onset_ok, rows.size());
  return contrast_ok == rows.size() && onset_ok == rows.size();
}

// The growth table: contrast by press depth on the neo-Hookean twins; true when the
// calibrated law meets the contrast mark at every press and the onset mark on every twin.
bool print_growth(const std::vector<fidelity::Growth>& twins) {
  std::printf("\nContrast growing with the press: neo-Hookean FEM twins (an inclusion at 5x and at 1x on one mesh, "
              "geometric nonlinearity, edge pinned) against the calibrated law pressed as deep.\n");
  bool met = true;
  for (const auto& g : twins) {
    const auto& first = g.rows.front();
    std::printf("%.0f mm layer, r %.0f mm, centre %.0f mm deep, %gx%s:\n  %8s | %7s | %10s %7s\n", first.thickness * 1e3,
                first.radius * 1e3, first.depth * 1e3, first.ratio,
                g.finger ? ", the 8 mm rounded finger" : "",
                "press", "FEM", "calibrated", "error");
    for (const auto& r : g.rows) {
      const bool ok = fidelity::contrast_met(r.calibrated, r.fem);
      met = met && ok;
      std::printf("  %5.2f mm | %7.4f | %10.4f %+6.3f%s\n", r.press * 1e3, r.fem, r.calibrated, r.calibrated - r.fem,
                  ok ? " " : "!");
    }
    const bool ok = fidelity::onset_met(g.calibrated_onset, g.fem_onset);
    met = met && ok;
    std::printf("  onset (to %.2f mm, the twin's reach): FEM %s, calibrated %s%s\n", g.rows.back().press * 1e3,
                onset_text(g.fem_onset).c_str(), onset_text(g.calibrated_onset).c_str(),
                ok ? "" : " (more than 2 mm off)");
  }
  return met;
}

// The lateral table: contrast beside the axis and the half-width of the extra force; true
// when the calibrated law meets the contrast mark at every offset and the half-width mark.
bool print_lateral(const std::vector<fidelity::Inclusion>& rows) {
  std::printf("\nBeside the pad's axis, 40 mm of 5 kPa (lateral_slab40_E5k_linear.csv, 3-D FEM): contrast by the "
              "finger's offset from the tumour, and the half-width of the extra force (where C - 1 halves).\n");
  bool met = true;
  for (const auto& g : fidelity::by_inclusion(rows)) {
    std::printf("r %.0f mm, centre %.0f mm deep, %gx:\n  %9s | %7s | %10s %7s | %8s\n", g[0].radius * 1e3,
                g[0].depth * 1e3, g[0].ratio, "offset", "FEM", "calibrated", "error", "paper's");
    for (const auto& r : g) {
      const bool ok = fidelity::contrast_met(r.calibrated, r.fem);
      met = met && ok;
      std::printf("  %6.1f mm | %7.4f | %10.4f %+6.3f%s | %8.4f\n", r.offset * 1e3, r.fem, r.calibrated,
                  r.calibrated - r.fem, ok ? " " : "!", r.paper);
    }
    const double fem = fidelity::half_width(g, fidelity::Source::Fem);
    const double calibrated = fidelity::half_width(g, fidelity::Source::Calibrated);
    const double paper = fidelity::half_width(g, fidelity::Source::Paper);
    const bool ok = calibrated >= 0.0 && std::abs(calibrated - fem) <= kHalfWidthTolerance;
    met = met && ok;
    std::printf("  half-width: FEM %.1f mm, calibrated %.1f mm (%+.1f mm%s), paper's %s\n", fem * 1e3,
                calibrated * 1e3, (calibrated - fem) * 1e3, ok ? "" : ", more than 3 mm off",
                paper < 0.0 ? "none (nothing felt on the axis)" : half_width_text(paper, fem).c_str());
  }
  return met;
}

}  // namespace

int run_bench_fidelity(const std::filesystem::path& reference_dir, const std::filesystem::path& out_dir) {
  std::vector<Row> rows;
  std::vector<fidelity::Inclusion> on_axis, beside;
  std::vector<fidelity::Growth> growth;
  try {
    for (const auto& r : kReferences) {
      const Curve fem = read_curve(reference_dir / r.file);
      for (const auto law : {mat::ForceModel::Calibrated, mat::ForceModel::Paper}) rows.push_back(compare(r, fem, law));
    }
    on_axis = fidelity::on_axis(reference_dir);
    beside = fidelity::beside_axis(reference_dir);
    growth = fidelity::contrast_growth(reference_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palpa-cli: error: %s\n", e.what());
    return 2;
  }
  bool met = print_forces(rows, reference_dir);
  met = print_on_axis(on_axis) && met;
  met = print_growth(growth) && met;
  met = print_lateral(beside) && met;
  try {
    std::filesystem::create_directories(out_dir);
    write_csv(rows, out_dir / "fidelity.csv");
    fidelity::write_contrast_csv(on_axis, out_dir / "fidelity_contrast.csv");
    fidelity::write_lateral_csv(beside, out_dir / "fidelity_lateral.csv");
    fidelity::write_growth_csv(growth, out_dir / "fidelity_growth.csv");
    write_png(rows, out_dir / "fidelity.png");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palpa-cli: error: %s\n", e.what());
    return 2;
  }
  std::printf("wrote fidelity.csv, fidelity_contrast.csv, fidelity_lateral.csv, fidelity_growth.csv and fidelity.png "
              "into %s\n",
              out_dir.c_str());
  std::printf("calibrated law within %.0f %% of every force curve, and within the contrast, onset and half-width marks "
              "on every inclusion, under the pad and under the rounded finger: %s\n", 100.0 * kTolerance, met ? "yes" : "NO");
  return met ? 0 : 1;
}

}  // namespace palpa::cli
