// The support and the free surface of a label volume, column by column along the
// support's normal (docs/anatomy-import.md, "Label volumes").
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "palpa/anatomy/import_error.hpp"
#include "palpa/anatomy/surfaces.hpp"
#include "support_model.hpp"
#include "voxel_sampler.hpp"

namespace palpa::anatomy {

namespace {

bool is_soft(LabelClass c) { return LabelTable::soft(c); }
bool is_support(LabelClass c) { return c == LabelClass::Support; }
bool is_body(LabelClass c) { return c != LabelClass::Outside; }

// Samples are half voxels. A gap of air of up to 3 voxels inside the tissue is taken as
// tissue: where the skin's side is steep a column grazes its voxel steps, and a body's side
// may bulge a little over its base. Tissue 4 voxels thick or more under a wider gap is an
// overhang.
constexpr int kGapSamples = 6;
constexpr int kOverhangSamples = 8;

void check_labels(const LabelVolume& v, const LabelTable& table, const std::string& source) {
  if (v.voxel_count() == 0 || v.labels.size() != v.voxel_count()) throw ImportError(source + ": the volume holds no voxels");
  std::array<std::size_t, 5> per_class{};
  for (const auto& [label, count] : label_counts(v)) {
    const LabelEntry* entry = table.find(label);
    if (entry == nullptr && label == 0) {  // background, as every segmentation tool writes it
      per_class[static_cast<std::size_t>(LabelClass::Outside)] += count;
      continue;
    }
    if (entry == nullptr) {
      const auto first = static_cast<std::size_t>(std::find(v.labels.begin(), v.labels.end(), label) - v.labels.begin());
      const auto i = first % static_cast<std::size_t>(v.dims[0]);
      const auto j = first / static_cast<std::size_t>(v.dims[0]) % static_cast<std::size_t>(v.dims[1]);
      const auto k = first / (static_cast<std::size_t>(v.dims[0]) * static_cast<std::size_t>(v.dims[1]));
      throw ImportError(fmt::format("{}: label {}: {} voxels (the first at voxel ({}, {}, {})) have a label the table "
                                    "\"{}\" does not list",
                                    source, label, count, i, j, k, table.name));
    }
    per_class[static_cast<std::size_t>(entry->kind)] += count;
  }
  if (per_class[static_cast<std::size_t>(LabelClass::Tissue)] + per_class[static_cast<std::size_t>(LabelClass::Skin)] == 0) {
    throw ImportError(source + ": empty tissue: no voxel has a label of class tissue or skin");
  }
  if (per_class[static_cast<std::size_t>(LabelClass::Support)] == 0) {
    throw ImportError(source + ": no support: no voxel has a label of class support (the chest wall, pelvis or table "
                               "the body rests on)");
  }
}

struct Boundary {
  std::vector<Vec3> support;  // world midpoints between support voxels and soft neighbours
  Vec3 soft_centre = Vec3::Zero();
};

Boundary support_boundary(const VoxelSampler& sampler) {
  const LabelVolume& v = sampler.volume();
  Boundary out;
  Eigen::Vector3d soft_sum = Eigen::Vector3d::Zero();
  double soft_count = 0.0;
  for (int k = 0; k < v.dims[2]; ++k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      for (int i = 0; i < v.dims[0]; ++i) {
        const LabelClass c = sampler.class_of(v.labels[v.index(i, j, k)]);
        if (is_soft(c)) {
          soft_sum += Eigen::Vector3d(i, j, k);
          soft_count += 1.0;
        }
        if (c != LabelClass::Support) continue;
        static constexpr int kSteps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const auto& d : kSteps) {
          const int a = i + d[0], b = j + d[1], e = k + d[2];
          if (a < 0 || b < 0 || e < 0 || a >= v.dims[0] || b >= v.dims[1] || e >= v.dims[2]) continue;
          if (is_soft(sampler.class_of(v.labels[v.index(a, b, e)]))) {
            out.support.push_back(to_vec3(v.world(i + 0.5 * d[0], j + 0.5 * d[1], k + 0.5 * d[2])));
          }
        }
      }
    }
  }
  if (out.support.empty()) throw ImportError("no support: the tissue touches no voxel of class support");
  soft_sum /= soft_count;
  out.soft_centre = to_vec3(v.world(soft_sum.x(), soft_sum.y(), soft_sum.z()));
  return out;
}

// The sampled square over the support: the volume's corners projected, one sample a voxel.
void size_fields(const LabelVolume& v, const Frame& f, SurfacePair& pair, double& h_lo, double& h_hi) {
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo, t_lo = s_lo, t_hi = -s_lo;
  h_lo = s_lo;
  h_hi = -s_lo;
  for (int c = 0; c < 8; ++c) {
    const Vec3 q = f.to_local(to_vec3(v.world((c & 1) ? v.dims[0] - 1 : 0, (c & 2) ? v.dims[1] - 1 : 0,
                                              (c & 4) ? v.dims[2] - 1 : 0)));
    s_lo = std::min(s_lo, q.x());
    s_hi = std::max(s_hi, q.x());
    t_lo = std::min(t_lo, q.y());
    t_hi = std::max(t_hi, q.y());
    h_lo = std::min(h_lo, q.z());
    h_hi = std::max(h_hi, q.z());
  }
  const double step = *std::min_element(v.spacing.begin(), v.spacing.end());
  for (HeightField* field : {&pair.bottom, &pair.top}) {
    field->step = step;
    field->s0 = s_lo;
    field->t0 = t_lo;
    field->ns = static_cast<int>(std::ceil((s_hi - s_lo) / step)) + 1;
    field->nt = static_cast<int>(std::ceil((t_hi - t_lo) / step)) + 1;
    field->h.assign(static_cast<std::size_t>(field->ns) * static_cast<std::size_t>(field->nt), kNoSurface);
  }
}

// Where, between heights lo (member) and hi (not), the indicator crosses 0.5.
double crossing(const VoxelSampler& sampler, const Frame& f, double s, double t, double lo, double hi,
                bool (*member)(LabelClass)) {
  for (int it = 0; it < 12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (sampler.share(sampler.index_of(f.to_world(s, t, mid)), member) >= 0.5 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Column {
  double bottom = kNoSurface, top = kNoSurface;
};

// One column read from above: the first body voxel met is the skin (or, with no tissue, the
// support); the tissue runs down, across air gaps of at most kGapSamples, to the support,
// which is the bottom. Where the tissue ends in air instead, the bottom is left to the
// support model, and tissue found again below that air (a run of kOverhangSamples or more)
// is an overhang. Anything inside the support (vessels crossing the muscle) is never read.
Column read_column(const VoxelSampler& sampler, const Frame& f, double s, double t, double h_lo, double h_hi,
                   double dh, const std::string& source) {
  const int steps = static_cast<int>((h_hi - h_lo) / dh) + 1;
  const Vec3 start = sampler.index_of(f.to_world(s, t, h_lo));
  const Vec3 step = sampler.index_of(f.to_world(s, t, h_lo + dh)) - start;
  const auto height = [&](int q) { return h_lo + q * dh; };
  int q = steps - 1;
  while (q >= 0 && !is_body(sampler.nearest(start + q * step))) --q;
  Column col;
  if (q < 0) return col;
  if (is_support(sampler.nearest(start + q * step))) {
    col.bottom = col.top = crossing(sampler, f, s, t, height(q), height(q + 1), is_support);
    return col;
  }
  col.top = crossing(sampler, f, s, t, height(q), height(q + 1), is_body);
  int lowest = q, gap = 0;
  for (--q; q >= 0 && gap <= kGapSamples; --q) {
    const LabelClass c = sampler.nearest(start + q * step);
    if (is_support(c)) {
      col.bottom = crossing(sampler, f, s, t, height(q), height(lowest), is_support);
      return col;
    }
    if (is_soft(c)) lowest = q, gap = 0;
    else ++gap;
  }
  for (int run = 0; q >= 0; --q) {
    const LabelClass c = sampler.nearest(start + q * step);
    run = is_soft(c) ? run + 1 : 0;
    if (is_support(c)) break;
    if (run >= kOverhangSamples) {
      throw ImportError(fmt::format("{}: overhang at {}: tissue above air; the free surface must be a height field "
                                    "over the support",
                                    source, millimetres(f.to_world(s, t, height(lowest)))));
    }
  }
  return col;
}

// Columns with no support under them take the support model's height.
void fill_from_model(SurfacePair& pair, const SupportModel& model) {
  for (int b = 0; b < pair.bottom.nt; ++b) {
    for (int a = 0; a < pair.bottom.ns; ++a) {
      double& bottom = pair.bottom.at(a, b);
      double& top = pair.top.at(a, b);
      if (std::isnan(bottom)) bottom = model.height(pair.bottom.s_at(a), pair.bottom.t_at(b));
      if (std::isnan(top) || top < bottom) top = bottom;
    }
  }
}

}  // namespace

SurfacePair surfaces_from_volume(const LabelVolume& volume, const LabelTable& table, const std::string& source) {
  check_labels(volume, table, source);
  const VoxelSampler sampler(volume, table);
  const double resolution = *std::max_element(volume.spacing.begin(), volume.spacing.end());
  Boundary boundary;
  SupportModel model;
  try {
    boundary = support_boundary(sampler);
    model = fit_support(boundary.support, boundary.soft_centre, resolution);
  } catch (const ImportError& e) {
    throw ImportError(source + ": " + e.what());
  }
  SurfacePair pair;
  pair.frame = model.frame;
  pair.support_kind = model.curved ? "curved" : "plane";
  pair.resolution = resolution;
  double h_lo = 0.0, h_hi = 0.0;
  size_fields(volume, model.frame, pair, h_lo, h_hi);
  const double dh = 0.5 * *std::min_element(volume.spacing.begin(), volume.spacing.end());
  for (int b = 0; b < pair.top.nt; ++b) {
    for (int a = 0; a < pair.top.ns; ++a) {
      const Column col = read_column(sampler, model.frame, pair.top.s_at(a), pair.top.t_at(b), h_lo, h_hi, dh, source);
      pair.bottom.at(a, b) = col.bottom;
      pair.top.at(a, b) = col.top;
    }
  }
  fill_from_model(pair, model);
  // The labels' 0.5 level is a staircase of voxel steps; a Gaussian of one voxel lays it
  // on the surface the voxels sample (it flattens a 70 mm sphere by 0.01 mm at 1 mm voxels).
  pair.bottom = blurred(pair.bottom, resolution);
  pair.top = blurred(pair.top, resolution);
  for (std::size_t k = 0; k < pair.top.h.size(); ++k) pair.top.h[k] = std::max(pair.top.h[k], pair.bottom.h[k]);
  return pair;
}

std::string millimetres(const Vec3& p) {
  return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", p.x() * 1e3, p.y() * 1e3, p.z() * 1e3);
}

}  // namespace palpa::anatomy
