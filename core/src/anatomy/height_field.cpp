#include "palpa/anatomy/height_field.hpp"

#include <algorithm>

namespace palpa::anatomy {

namespace {

// The cell and the offsets in it of (s, t), clamped to the sampled square.
struct Cell {
  int a = 0, b = 0;
  double fs = 0.0, ft = 0.0;
};

Cell locate(const HeightField& f, double s, double t) {
  const double x = std::clamp((s - f.s0) / f.step, 0.0, static_cast<double>(f.ns - 1));
  const double y = std::clamp((t - f.t0) / f.step, 0.0, static_cast<double>(f.nt - 1));
  Cell c;
  c.a = std::min(static_cast<int>(x), std::max(f.ns - 2, 0));
  c.b = std::min(static_cast<int>(y), std::max(f.nt - 2, 0));
  c.fs = x - c.a;
  c.ft = y - c.b;
  return c;
}

}  // namespace

double HeightField::sample(double s, double t) const {
  double height = 0.0, ds = 0.0, dt = 0.0;
  return sample(s, t, height, ds, dt) ? height : kNoSurface;
}

bool HeightField::sample(double s, double t, double& height, double& dh_ds, double& dh_dt) const {
  if (ns < 2 || nt < 2) return false;
  const Cell c = locate(*this, s, t);
  const double h00 = at(c.a, c.b), h10 = at(c.a + 1, c.b), h01 = at(c.a, c.b + 1), h11 = at(c.a + 1, c.b + 1);
  if (std::isnan(h00) || std::isnan(h10) || std::isnan(h01) || std::isnan(h11)) return false;
  const double lo = h00 + (h10 - h00) * c.fs, hi = h01 + (h11 - h01) * c.fs;
  height = lo + (hi - lo) * c.ft;
  dh_ds = ((h10 - h00) * (1.0 - c.ft) + (h11 - h01) * c.ft) / step;
  dh_dt = (hi - lo) / step;
  return true;
}

namespace {

// One separable pass along a (the sample index's stride `stride`, `count` samples per line).
void blur_pass(const std::vector<double>& in, std::vector<double>& out, const std::vector<double>& kernel, int count,
               int lines, std::size_t stride, std::size_t line_stride) {
  const int half = static_cast<int>(kernel.size() / 2);
  for (int line = 0; line < lines; ++line) {
    for (int a = 0; a < count; ++a) {
      const std::size_t here = static_cast<std::size_t>(line) * line_stride + static_cast<std::size_t>(a) * stride;
      if (std::isnan(in[here])) continue;
      double sum = 0.0, weight = 0.0;
      for (int d = -half; d <= half; ++d) {
        const int b = std::clamp(a + d, 0, count - 1);
        const double v = in[static_cast<std::size_t>(line) * line_stride + static_cast<std::size_t>(b) * stride];
        if (std::isnan(v)) continue;
        sum += kernel[static_cast<std::size_t>(d + half)] * v;
        weight += kernel[static_cast<std::size_t>(d + half)];
      }
      out[here] = sum / weight;
    }
  }
}

}  // namespace

HeightField blurred(const HeightField& field, double sigma) {
  const double samples = sigma / field.step;
  if (!(samples > 0.1)) return field;
  const int half = static_cast<int>(std::ceil(3.0 * samples));
  std::vector<double> kernel(static_cast<std::size_t>(2 * half + 1));
  for (int d = -half; d <= half; ++d) kernel[static_cast<std::size_t>(d + half)] = std::exp(-0.5 * d * d / (samples * samples));
  HeightField out = field;
  std::vector<double> along_s = field.h;
  blur_pass(field.h, along_s, kernel, field.ns, field.nt, 1, static_cast<std::size_t>(field.ns));
  blur_pass(along_s, out.h, kernel, field.nt, field.ns, static_cast<std::size_t>(field.ns), 1);
  return out;
}

double surface_distance(const SurfacePair& pair, const HeightField& field, const Vec3& p) {
  const Vec3 q = pair.frame.to_local(p);
  double h = 0.0, ds = 0.0, dt = 0.0;
  if (!field.sample(q.x(), q.y(), h, ds, dt)) return kNoSurface;
  // The surface near its sample as the plane h + grad h . d: the distance along its normal.
  return std::abs(q.z() - h) / std::sqrt(1.0 + ds * ds + dt * dt);
}

}  // namespace palpa::anatomy
