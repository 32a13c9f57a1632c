#include "column_tissue.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>

#include "palpa/mat/layer_stiffness.hpp"
#include "voxel_sampler.hpp"

namespace palpa::anatomy {

namespace {

// Layers thinner than this (m) merge into their neighbour; thicknesses are keyed to it.
constexpr double kQuantum = 0.1e-3;

// The column's layers from the skin down: runs of one modulus. A lesion's voxels count as
// the tissue around them (the lesion is its own tumour); air or support inside is skipped.
std::vector<mat::TissueLayer> column_layers(const VoxelSampler& sampler, const LabelTable& table, const Frame& f,
                                            double s, double t, double bottom, double top) {
  const auto& v = sampler.volume();
  const double dh = 0.25 * *std::min_element(v.spacing.begin(), v.spacing.end());
  std::vector<mat::TissueLayer> layers;
  for (double h = top - 0.5 * dh; h > bottom; h -= dh) {
    const int label = sampler.nearest_label(sampler.index_of(f.to_world(s, t, h)));
    const LabelEntry* entry = label < 0 ? nullptr : table.find(label);
    if (entry == nullptr || !LabelTable::soft(entry->kind)) continue;
    double modulus = entry->modulus;
    if (entry->kind == LabelClass::Lesion) {
      if (layers.empty()) continue;
      modulus = layers.back().modulus;
    }
    if (!layers.empty() && layers.back().modulus == modulus) layers.back().thickness += dh;
    else layers.push_back({dh, modulus});
  }
  return layers;
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

}  // namespace

std::vector<double> column_moduli(const LabelVolume& volume, const LabelTable& table, const SurfacePair& pair,
                                  const FittedBody& fitted, double nu) {
  const VoxelSampler sampler(volume, table);
  const int rows = fitted.grid.rows, cols = fitted.grid.cols;
  std::vector<double> moduli(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), 0.0);
  ModulusCache cache(nu);
  // Two threads (the machines Palpa targets have two cores or more); each takes every other row.
  const auto work = [&](int first) {
    for (int i = first; i < rows; i += 2) {
      for (int j = 0; j < cols; ++j) {
        const double s = fitted.s_sites[static_cast<std::size_t>(i)], t = fitted.t_sites[static_cast<std::size_t>(j)];
        const double bottom = pair.bottom.sample(s, t), top = pair.top.sample(s, t);
        if (!(top - bottom > 0.0)) continue;
        const auto layers = simplified(column_layers(sampler, table, pair.frame, s, t, bottom, top));
        moduli[static_cast<std::size_t>(i * cols + j)] = layers.empty() ? 0.0 : cache(layers);
      }
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
  return moduli;
}

double dominant_stiffening(const LabelVolume& volume, const LabelTable& table) {
  std::vector<std::size_t> count(65536, 0);
  for (const std::uint16_t label : volume.labels) ++count[label];
  double b = 0.0;
  std::size_t most = 0;
  for (const auto& [label, entry] : table.labels) {
    if ((entry.kind == LabelClass::Tissue || entry.kind == LabelClass::Skin) && count[static_cast<std::size_t>(label)] > most) {
      most = count[static_cast<std::size_t>(label)];
      b = entry.stiffening;
    }
  }
  return b;
}

}  // namespace palpa::anatomy
