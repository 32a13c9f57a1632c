#include "column_tissue.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/mat/layer_stiffness.hpp"
#include "palpa/mat/mat_body.hpp"
#include "voxel_sampler.hpp"

namespace palpa::anatomy {

namespace {

// Layers thinner than this (m) merge into their neighbour; thicknesses are keyed to it.
constexpr double kQuantum = 0.1e-3;
// Columns thinner than this many voxels take the median of the others.
constexpr double kThinColumnVoxels = 3.0;

// The column's layers from the skin down: runs of one modulus. A lesion's voxels count as
// the tissue around them (the lesion is its own tumour); air or support inside is skipped.
struct ColumnLayers {
  std::vector<mat::TissueLayer> layers;
  double skin = 0.0;  // m of skin at the top, along the column
};

ColumnLayers column_layers(const VoxelSampler& sampler, const LabelTable& table, const Frame& f, double s, double t,
                           double bottom, double top) {
  const auto& v = sampler.volume();
  const double dh = 0.25 * *std::min_element(v.spacing.begin(), v.spacing.end());
  ColumnLayers out;
  auto& layers = out.layers;
  bool at_top = true;
  for (double h = top - 0.5 * dh; h > bottom; h -= dh) {
    const auto label = sampler.nearest_label(sampler.index_of(f.to_world(s, t, h)));
    const LabelEntry* entry = label ? table.find(*label) : nullptr;
    if (entry == nullptr || !LabelTable::soft(entry->kind)) continue;
    at_top = at_top && entry->kind == LabelClass::Skin;
    if (at_top) out.skin += dh;
    double modulus = entry->modulus;
    if (entry->kind == LabelClass::Lesion) {
      if (layers.empty()) continue;
      modulus = layers.back().modulus;
    }
    if (!layers.empty() && layers.back().modulus == modulus) layers.back().thickness += dh;
    else layers.push_back({dh, modulus});
  }
  return out;
}

// The skin as one layer of the body's own thickness: along a column the voxelized skin is
// one to three voxels thick as the column meets its staircase, and that noise would make
// the tissue's stiffness jump from point to point. The body's skin is the lower quartile of
// the columns' skin (the columns that cross it squarely, not obliquely).
double skin_thickness(const std::vector<ColumnLayers>& columns) {
  std::vector<double> skins;
  for (const auto& c : columns) {
    if (c.skin > 0.0) skins.push_back(c.skin);
  }
  if (skins.empty()) return 0.0;
  std::nth_element(skins.begin(), skins.begin() + static_cast<std::ptrdiff_t>(skins.size() / 4), skins.end());
  return skins[skins.size() / 4];
}

void set_skin(ColumnLayers& c, double skin) {
  if (c.skin <= 0.0 || c.layers.size() < 2) return;  // a column of skin alone keeps it
  mat::TissueLayer& outer = c.layers[0];
  mat::TissueLayer& under = c.layers[1];
  const double moved = outer.thickness - std::clamp(skin, kQuantum, outer.thickness + under.thickness - kQuantum);
  outer.thickness -= moved;
  under.thickness += moved;
}

// Layers rounded to kQuantum, the thinnest merged away, so that similar columns share a key.
std::vector<mat::TissueLayer> simplified(std::vector<mat::TissueLayer> layers) {
  std::vector<mat::TissueLayer> out;
  for (const auto& l : layers) {
    const double thickness = std::round(l.thickness / kQuantum) * kQuantum;
    if (thickness <= 0.0) continue;
    if (!out.empty() && out.back().modulus == l.modulus) out.back().thickness += thickness;
    else out.push_back({thickness, l.modulus});
  }
  return out;
}

double one_modulus(std::vector<mat::TissueLayer> layers, double nu) {
  if (layers.empty()) return 0.0;
  if (layers.size() == 1) return layers.front().modulus;
  double lo = layers.front().modulus, hi = lo, total = 0.0, weighted = 0.0;
  for (const auto& l : layers) {
    lo = std::min(lo, l.modulus), hi = std::max(hi, l.modulus);
    total += l.thickness, weighted += l.thickness * l.modulus;
  }
  // Within 2 % the layers are one tissue (fat and glandular tissue differ by 0.3 %).
  if (hi <= 1.02 * lo) return weighted / total;
  return mat::column_modulus(layers, nu);
}

class ModulusCache {
 public:
  explicit ModulusCache(double nu) : nu_(nu) {}
  double operator()(const std::vector<mat::TissueLayer>& layers) {
    std::vector<std::pair<long, double>> key;
    for (const auto& l : layers) key.emplace_back(std::lround(l.thickness / kQuantum), l.modulus);
    {
      const std::lock_guard lock(mutex_);
      const auto it = cache_.find(key);
      if (it != cache_.end()) return it->second;
    }
    const double e = one_modulus(layers, nu_);
    const std::lock_guard lock(mutex_);
    cache_.emplace(std::move(key), e);
    return e;
  }

 private:
  double nu_;
  std::mutex mutex_;
  std::map<std::vector<std::pair<long, double>>, double> cache_;
};

// The moduli as the fingertip pad meets them: a pad of radius a presses the tissue over its
// whole footprint, and the stress under it spreads about as far again, so each point takes
// the Gaussian mean (sigma = a) of the columns around it: columns side by side under one
// rigid pad share its load, so their moduli add (an arithmetic mean, not a harmonic one).
std::vector<double> under_the_pad(const std::vector<double>& moduli, const FittedBody& fitted) {
  const int rows = fitted.grid.rows, cols = fitted.grid.cols;
  const double sigma = mat::kFingertipPadRadius;
  std::vector<double> out(moduli.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      double sum = 0.0, weight = 0.0;
      for (int a = 0; a < rows; ++a) {
        const double ds = fitted.s_sites[static_cast<std::size_t>(a)] - fitted.s_sites[static_cast<std::size_t>(i)];
        if (std::abs(ds) > 3.0 * sigma) continue;
        for (int b = 0; b < cols; ++b) {
          const double dt = fitted.t_sites[static_cast<std::size_t>(b)] - fitted.t_sites[static_cast<std::size_t>(j)];
          const double w = std::exp(-0.5 * (ds * ds + dt * dt) / (sigma * sigma));
          sum += w * moduli[static_cast<std::size_t>(a * cols + b)];
          weight += w;
        }
      }
      out[static_cast<std::size_t>(i * cols + j)] = sum / weight;
    }
  }
  return out;
}

}  // namespace

std::vector<double> column_moduli(const LabelVolume& volume, const LabelTable& table, const SurfacePair& pair,
                                  const FittedBody& fitted, double nu) {
  const VoxelSampler sampler(volume, table);
  const double resolution = *std::max_element(volume.spacing.begin(), volume.spacing.end());
  const int rows = fitted.grid.rows, cols = fitted.grid.cols;
  std::vector<double> moduli(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), 0.0);
  std::vector<ColumnLayers> columns(moduli.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double s = fitted.s_sites[static_cast<std::size_t>(i)], t = fitted.t_sites[static_cast<std::size_t>(j)];
      const double bottom = pair.bottom.sample(s, t), top = pair.top.sample(s, t);
      // A column of a voxel or two at the rim is skin alone; its stiffness is the support's
      // wall beside it anyway, and a jump there makes the spline overshoot.
      if (!(top - bottom > kThinColumnVoxels * resolution)) continue;
      columns[static_cast<std::size_t>(i * cols + j)] = column_layers(sampler, table, pair.frame, s, t, bottom, top);
    }
  }
  const double skin = skin_thickness(columns);
  ModulusCache cache(nu);
  // Two threads (the machines Palpa targets have two cores or more); each takes every other point.
  const auto work = [&](std::size_t first) {
    for (std::size_t k = first; k < columns.size(); k += 2) {
      set_skin(columns[k], skin);
      const auto layers = simplified(columns[k].layers);
      moduli[k] = layers.empty() ? 0.0 : cache(layers);
    }
  };
  std::thread second(work, 1);
  work(0);
  second.join();
  std::vector<double> found;
  for (const double e : moduli) {
    if (e > 0.0) found.push_back(e);
  }
  if (found.empty()) return moduli;
  std::nth_element(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(found.size() / 2), found.end());
  const double median = found[found.size() / 2];
  for (double& e : moduli) {
    if (!(e > 0.0)) e = median;
  }
  return under_the_pad(moduli, fitted);
}

int smooth_until_fits(mat::BodyGrid& body) {
  for (int pass = 0;; ++pass) {
    mat::BodyGrid trial = body;
    trial.stiffness = mat::layer_stiffness_field(trial.modulus, trial.radius, trial.poisson);
    try {
      (void)mat::MatBody::fit(trial);
      return pass;
    } catch (const mat::FitError& e) {
      if (pass == 8) throw ImportError(fmt::format("the tissue's modulus cannot be made smooth enough: {}", e.what()));
    }
    const std::vector<double> was = body.modulus;
    for (int i = 0; i < body.rows; ++i) {
      for (int j = 0; j < body.cols; ++j) {
        double sum = 0.0;
        int count = 0;
        for (int a = std::max(i - 1, 0); a <= std::min(i + 1, body.rows - 1); ++a) {
          for (int b = std::max(j - 1, 0); b <= std::min(j + 1, body.cols - 1); ++b, ++count) {
            sum += was[static_cast<std::size_t>(a * body.cols + b)];
          }
        }
        body.modulus[static_cast<std::size_t>(i * body.cols + j)] = sum / count;
      }
    }
  }
}

double dominant_stiffening(const LabelVolume& volume, const LabelTable& table) {
  const auto count = label_counts(volume);
  double b = 0.0;
  std::size_t most = 0;
  for (const auto& [label, entry] : table.labels) {
    const auto it = count.find(label);
    if ((entry.kind == LabelClass::Tissue || entry.kind == LabelClass::Skin) && it != count.end() && it->second > most) {
      most = it->second;
      b = entry.stiffening;
    }
  }
  return b;
}

}  // namespace palpa::anatomy
