#include "bench_fidelity_contrast.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "palpa/author/presets.hpp"
#include "palpa/io/case_file.hpp"

namespace palpa::cli::fidelity {
namespace {

// m. The linear sweeps stand for the small-strain limit, so the calibrated law is read there
// too (TumourContrast::compressed off: the same contrast at every press); its growth with
// the press is checked against the neo-Hookean twins (bench_fidelity_growth.hpp).
constexpr double kCalibratedPress = 0.002;
constexpr double kPaperPress = 0.004;       // m: where the paper's tumour spring has engaged
constexpr double kOnsetStep = 0.00025;      // m: the press depths scanned for the onset
constexpr double kOnsetReach = 0.40;        // share of the thickness scanned
constexpr double kOnsetTolerance = 0.002;   // m

struct SweepFile {
  const char* file;
  double thickness;  // m
};
constexpr SweepFile kOnAxis[] = {{"contrast_slab40_E5k_linear.csv", 0.040},
                                 {"contrast_slab30_E5k_linear.csv", 0.030},
                                 {"contrast_slab20_E5k_linear.csv", 0.020}};
constexpr SweepFile kLateral{"lateral_slab40_E5k_linear.csv", 0.040};

// Rows of `columns` numbers after a header starting with "inclusion_radius_m,".
std::vector<std::vector<double>> read_rows(const std::filesystem::path& path, std::size_t columns) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot read (give --reference DIR)");
  std::string line;
  if (!std::getline(in, line) || line.rfind("inclusion_radius_m,", 0) != 0) {
    throw std::runtime_error(path.string() + ": line 1: expected the header inclusion_radius_m,...");
  }
  std::vector<std::vector<double>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::size_t at = 0;
    while (at <= line.size() && row.size() < columns) {
      const std::size_t comma = std::min(line.find(',', at), line.size());
      char* end = nullptr;
      const std::string cell = line.substr(at, comma - at);
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0' || !std::isfinite(v)) break;
      row.push_back(v);
      at = comma + 1;
    }
    if (row.size() != columns || !(row[0] > 0.0) || !(row[columns - 1] > 0.0)) {
      throw std::runtime_error(fmt::format("{}: line {}: expected {} numbers", path.string(), number, columns));
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw std::runtime_error(path.string() + ": no inclusion");
  return rows;
}

io::CaseFile slab(double thickness, mat::ForceModel law, mat::Indenter indenter) {
  io::CaseFile file = author::make_modulus_slab(kSlabWidth, thickness, kLayerModulus, law);
  file.indenter = indenter;
  return file;
}

}  // namespace

scene::Scene plain_slab(double thickness, mat::ForceModel law, mat::Indenter indenter) {
  return scene::Scene::build(slab(thickness, law, indenter), "slab");
}

scene::Scene with_tumour(const Inclusion& r, mat::ForceModel law, double stiffness) {
  io::CaseFile file = slab(r.thickness, law, r.indenter);
  const auto plain = scene::Scene::build(file, "slab");
  std::array<double, 3> top{};
  plain.body(0).body.top().evaluate(0.5, 0.5, top);
  mat::Tumour t;
  t.body = file.bodies[0].id;
  t.center = {top[0] + r.offset, top[1], top[2] - r.depth};
  t.radius = r.radius;
  if (stiffness > 0.0) t.stiffness = stiffness; else t.modulus = r.ratio * kLayerModulus;
  file.tumours.push_back(t);
  return scene::Scene::build(io::parse_case(io::to_json(file).dump(), "slab with a tumour"), "slab with a tumour");
}

std::vector<std::array<double, 2>> read_force_curve(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot read (give --reference DIR)");
  std::string line;
  if (!std::getline(in, line) || line.rfind("depth_m,force_n", 0) != 0) {
    throw std::runtime_error(path.string() + ": line 1: expected the header depth_m,force_n");
  }
  std::vector<std::array<double, 2>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::istringstream row(line);
    double d = 0.0, f = 0.0;
    char comma = 0;
    if (!(row >> d >> comma >> f) || comma != ',' || !std::isfinite(d) || !std::isfinite(f) || d < 0.0) {
      throw std::runtime_error(fmt::format("{}: line {}: expected depth_m,force_n", path.string(), number));
    }
    if (d > 0.0) rows.push_back({d, f});
  }
  if (rows.empty()) throw std::runtime_error(path.string() + ": no depth above 0");
  return rows;
}

double onset(const scene::Scene& tumour, const scene::Scene& plain, double reach, const scene::ProbeOptions& options) {
  for (double d = kOnsetStep; d <= reach + 1e-12; d += kOnsetStep) {
    if (centre_force(tumour, d, options) >= kOnsetContrast * centre_force(plain, d, options)) return d;
  }
  return -1.0;
}

namespace {

// Fills in Palpa's contrast (and, when `onsets`, the onset depths) of each row.
void evaluate(std::vector<Inclusion>& rows, bool onsets) {
  for (auto& r : rows) {
    const auto calibrated_plain = plain_slab(r.thickness, mat::ForceModel::Calibrated, r.indenter);
    const auto paper_plain = plain_slab(r.thickness, mat::ForceModel::Paper, r.indenter);
    const auto calibrated = with_tumour(r, mat::ForceModel::Calibrated, 0.0);
    // The half-space rule of docs/case-authoring.md for a tumour's spring: k_t = 0.02 m x E_t.
    const auto paper = with_tumour(r, mat::ForceModel::Paper, 0.02 * r.ratio * kLayerModulus);
    scene::ProbeOptions small_strain;
    small_strain.force.contrast.compressed = false;
    r.calibrated = centre_force(calibrated, kCalibratedPress, small_strain) /
                   centre_force(calibrated_plain, kCalibratedPress, small_strain);
    r.paper = centre_force(paper, kPaperPress) / centre_force(paper_plain, kPaperPress);
    if (!onsets) continue;
    r.fem_onset = r.fem >= kOnsetContrast ? 0.0 : -1.0;  // linear: the same contrast at every press
    r.calibrated_onset = onset(calibrated, calibrated_plain, kOnsetReach * r.thickness, small_strain);
    r.paper_onset = onset(paper, paper_plain, kOnsetReach * r.thickness);
  }
}

void write_onset(std::ofstream& out, double onset) {
  if (onset >= 0.0) out << fmt::format("{:.5f}", onset);
}

}  // namespace

double centre_force(const scene::Scene& scene, double depth, const scene::ProbeOptions& options) {
  std::array<double, 3> top{};
  scene.body(0).body.top().evaluate(0.5, 0.5, top);
  auto state = scene.make_state();
  return scene.probe(palpa::Vec3(top[0], top[1], top[2] - depth), state, options).force.total.norm();
}

bool contrast_met(double model, double fem) { return std::abs(model - fem) <= std::max(0.2 * (fem - 1.0), 0.02); }

bool onset_met(double model, double fem) {
  if (model < 0.0 || fem < 0.0) return model < 0.0 && fem < 0.0;
  return std::abs(model - fem) <= kOnsetTolerance;
}

std::vector<Inclusion> on_axis(const std::filesystem::path& reference_dir) {
  std::vector<Inclusion> rows;
  for (const auto& f : kOnAxis) {
    // inclusion_radius_m,inclusion_depth_m,modulus_ratio,force_n,twin_force_n,contrast
    for (const auto& v : read_rows(reference_dir / f.file, 6)) rows.push_back({f.thickness, v[0], v[1], v[2], 0.0, v[5]});
  }
  evaluate(rows, true);
  return rows;
}

std::vector<Inclusion> beside_axis(const std::filesystem::path& reference_dir) {
  std::vector<Inclusion> rows;
  // inclusion_radius_m,inclusion_depth_m,modulus_ratio,offset_m,force_n,twin_force_n,contrast
  for (const auto& v : read_rows(reference_dir / kLateral.file, 7)) {
    rows.push_back({kLateral.thickness, v[0], v[1], v[2], v[3], v[6]});
  }
  evaluate(rows, false);
  return rows;
}

std::vector<std::vector<Inclusion>> by_inclusion(const std::vector<Inclusion>& rows) {
  std::vector<std::vector<Inclusion>> groups;
  for (const auto& r : rows) {
    auto same = [&](const std::vector<Inclusion>& g) {
      return g[0].radius == r.radius && g[0].depth == r.depth && g[0].ratio == r.ratio;
    };
    auto it = std::find_if(groups.begin(), groups.end(), same);
    if (it == groups.end()) groups.push_back({r}); else it->push_back(r);
  }
  for (auto& g : groups) {
    std::sort(g.begin(), g.end(), [](const Inclusion& a, const Inclusion& b) { return a.offset < b.offset; });
  }
  return groups;
}

double half_width(const std::vector<Inclusion>& rows, Source which) {
  auto extra = [which](const Inclusion& r) {
    return (which == Source::Fem ? r.fem : which == Source::Calibrated ? r.calibrated : r.paper) - 1.0;
  };
  if (rows.empty() || !(extra(rows.front()) > 0.0)) return -1.0;  // nothing felt on the axis
  const double half = 0.5 * extra(rows.front());
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double a = extra(rows[k - 1]), b = extra(rows[k]);
    if (b <= half && a > half) return rows[k - 1].offset + (a - half) / (a - b) * (rows[k].offset - rows[k - 1].offset);
  }
  return rows.back().offset;  // never halves within the sweep
}

void write_contrast_csv(const std::vector<Inclusion>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "inclusion_radius_m,inclusion_depth_m,modulus_ratio,fem_contrast,calibrated_contrast,paper_contrast,"
         "thickness_m,fem_onset_m,calibrated_onset_m,paper_onset_m\n";
  for (const auto& r : rows) {
    out << fmt::format("{:.4f},{:.4f},{:g},{:.5f},{:.5f},{:.5f},{:.3f},", r.radius, r.depth, r.ratio, r.fem,
                       r.calibrated, r.paper, r.thickness);
    write_onset(out, r.fem_onset);
    out << ',';
    write_onset(out, r.calibrated_onset);
    out << ',';
    write_onset(out, r.paper_onset);
    out << '\n';
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void write_lateral_csv(const std::vector<Inclusion>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "inclusion_radius_m,inclusion_depth_m,modulus_ratio,offset_m,fem_contrast,calibrated_contrast,"
         "paper_contrast\n";
  for (const auto& r : rows) {
    out << fmt::format("{:.4f},{:.4f},{:g},{:.4f},{:.5f},{:.5f},{:.5f}\n", r.radius, r.depth, r.ratio, r.offset, r.fem,
                       r.calibrated, r.paper);
  }
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

}  // namespace palpa::cli::fidelity
