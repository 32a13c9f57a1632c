#include "palpa/deform/deformed_body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "palpa/deform/control_point_modification.hpp"
#include "palpa/spline/knot_refinement.hpp"
#include "../common/numeric.hpp"

namespace palpa::deform {
namespace {

// Components of a control point's displacement: the skeleton's x y z and radius, then the
// top contour's x y z, then the bottom contour's x y z.
constexpr int kSkeletonXyz = 0;
constexpr int kRadius = 3;
constexpr int kTop = 4;
constexpr int kBottom = 7;


// m: a displacement this small is invisible (the tessellation tolerance is 0.2 mm) and
// changes no force (the force is computed on the rest body).
constexpr double kSnap = 1e-5;

// How many pieces each non-empty knot span of one direction needs so that no piece is
// longer than `span` on the top contour (chords over nine lines across), capped so the
// direction keeps at most `max_points` control points.
std::vector<int> pieces_for(const spline::BSplineSurface& top, bool along_u, double span, int max_points) {
  const auto& knots = along_u ? top.knots_u() : top.knots_v();
  const int existing = along_u ? top.rows() : top.cols();
  std::vector<int> pieces;
  std::vector<double> length;
  std::array<double, 3> a{}, b{};
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    if (!(knots[k + 1] > knots[k])) continue;
    double longest = 0.0;
    for (int line = 0; line <= 8; ++line) {
      const double w = line / 8.0;
      along_u ? top.evaluate(knots[k], w, a) : top.evaluate(w, knots[k], a);
      along_u ? top.evaluate(knots[k + 1], w, b) : top.evaluate(w, knots[k + 1], b);
      longest = std::max(longest, std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]));
    }
    length.push_back(longest);
    pieces.push_back(std::max(1, static_cast<int>(std::ceil(longest / span))));
  }
  // Over the cap: scale every span's pieces down alike (the longest spans keep the most).
  int added = 0;
  for (const int n : pieces) added += n - 1;
  const int room = std::max(0, max_points - existing);
  if (added > room && added > 0) {
    const double scale = static_cast<double>(room) / added;
    for (int& n : pieces) n = 1 + static_cast<int>(std::floor((n - 1) * scale));
  }
  return pieces;
}

spline::BSplineSurface refine_both(const spline::BSplineSurface& s, const std::vector<double>& in_u,
                                   const std::vector<double>& in_v) {
  return spline::refine_knots(spline::refine_knots(s, spline::Direction::U, in_u), spline::Direction::V, in_v);
}

}  // namespace

DisplayNet display_net(const mat::MatBody& rest, const DeformOptions& options) {
  if (!(options.display_span > 0.0)) return {rest.skeleton(), rest.top(), rest.bottom()};
  const auto& top = rest.top();
  const auto pu = pieces_for(top, true, options.display_span, options.max_display_points);
  const auto pv = pieces_for(top, false, options.display_span, options.max_display_points);
  const auto in_u = spline::split_spans(top.knots_u(), pu);
  const auto in_v = spline::split_spans(top.knots_v(), pv);
  return {refine_both(rest.skeleton(), in_u, in_v), refine_both(rest.top(), in_u, in_v),
          refine_both(rest.bottom(), in_u, in_v)};
}

DeformedBody::DeformedBody(const mat::MatBody& rest, const DeformOptions& options)
    : rest_(&rest),
      options_(options),
      net_(display_net(rest, options)),
      skeleton_(net_.skeleton),
      top_(net_.top),
      bottom_(net_.bottom),
      rows_(net_.skeleton.rows()),
      cols_(net_.skeleton.cols()) {
  const std::size_t n = idx(rows_ * cols_);
  x_.assign(n * kComponents, 0.0);
  v_.assign(n * kComponents, 0.0);
  k_.resize(n);
  b_.resize(n);
  m_.resize(n);
  steps_.resize(n);
  held_.assign(n, 0);
  active_.reserve(n);  // never more than every point: activate() never reallocates
  is_active_.assign(n, 0);
  // Each control point's spring, damper and mass: the material where that control point
  // acts most, i.e. the skeleton evaluated at its Greville parameters (the knot averages),
  // kept within the range of the authored values. The control points' own material
  // coefficients can overshoot far outside it (a single soft site among stiff ones gives
  // a negative one), which would leave a dent that never springs back. Every point keeps
  // at least 1 % of the body's largest stiffness so that it does return to rest.
  const auto& sk = net_.skeleton;
  std::array<double, mat::kSkeletonChannels> lo{};
  std::array<double, mat::kSkeletonChannels> hi{};
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  std::array<double, mat::kSkeletonChannels> value{};
  for (double u : rest.u_params()) {
    for (double v : rest.v_params()) {
      sk.evaluate(u, v, value);  // at the data sites: the authored values
      for (std::size_t c = 0; c < value.size(); ++c) {
        lo[c] = std::min(lo[c], value[c]);
        hi[c] = std::max(hi[c], value[c]);
      }
    }
  }
  const auto greville = [](const std::vector<double>& knots, int degree, int index) {
    double sum = 0.0;
    for (int k = 1; k <= degree; ++k) sum += knots[idx(index + k)];
    return sum / degree;
  };
  const double k_floor = 0.01 * std::max(hi[mat::kStiffness], 0.0);
  for (int i = 0; i < rows_; ++i) {
    for (int j = 0; j < cols_; ++j) {
      sk.evaluate(greville(sk.knots_u(), sk.degree_u(), i), greville(sk.knots_v(), sk.degree_v(), j), value);
      const std::size_t p = idx(i * cols_ + j);
      k_[p] = std::max(k_floor, std::clamp(value[mat::kStiffness], lo[mat::kStiffness], hi[mat::kStiffness]));
      b_[p] = std::max(0.0, std::clamp(value[mat::kDamping], lo[mat::kDamping], hi[mat::kDamping]));
      m_[p] = std::max(1e-9, std::clamp(value[mat::kMass], lo[mat::kMass], hi[mat::kMass]));
    }
  }
}

void DeformedBody::write_back(std::size_t point) {
  const int i = static_cast<int>(point) / cols_;
  const int j = static_cast<int>(point) % cols_;
  const double* x = &x_[point * kComponents];
  const auto rs = net_.skeleton.control_point(i, j);
  const auto rt = net_.top.control_point(i, j);
  const auto rb = net_.bottom.control_point(i, j);
  auto s = skeleton_.control_point(i, j);
  auto t = top_.control_point(i, j);
  auto b = bottom_.control_point(i, j);
  for (std::size_t c = 0; c < 3; ++c) {
    s[c] = rs[c] + x[kSkeletonXyz + c];
    t[c] = rt[c] + x[kTop + c];
    b[c] = rb[c] + x[kBottom + c];
  }
  s[mat::kRadius] = rs[mat::kRadius] + x[kRadius];
}

void DeformedBody::press(const contact::Contact& contact, const palpa::Vec3& q) {
  if (!contact.inside) {  // nothing to press: a probe outside lets go
    release();
    return;
  }
  const double u = contact.foot.u;
  const double v = contact.foot.v;
  const double depth = std::max(0.0, contact.depth);
  const double g = options_.scheme == Scheme::SkeletonMoves ? 1.0 : options_.g;
  const palpa::Vec3 n = contact.outward;

  // Targets: displacements from rest at (u, v). The near contour lands exactly on the
  // probe; the skeleton takes g of the press and the radius the rest (scheme (b); scheme
  // (a) is g = 1); the far contour then moves by (1 - 2g) depth n (0 for g = 1/2).
  const auto basis = net_.skeleton.basis(u, v);
  const bool top_near = contact.side > 0;
  std::array<double, 3> rest_near{};
  (top_near ? net_.top : net_.bottom).evaluate(basis, rest_near, 0, 3);
  std::array<double, kComponents> target{};
  for (std::size_t c = 0; c < 3; ++c) {
    target[kSkeletonXyz + c] = -g * depth * n[static_cast<Eigen::Index>(c)];
    const double near = q[static_cast<Eigen::Index>(c)] - rest_near[c];
    const double far = (1.0 - 2.0 * g) * depth * n[static_cast<Eigen::Index>(c)];
    target[kTop + c] = top_near ? near : far;
    target[kBottom + c] = top_near ? far : near;
  }
  target[kRadius] = -(1.0 - g) * depth;

  // The press's support, the (p+1) x (q+1) control points under (u, v), takes the whole
  // dent afresh every tick: those points are first put back at rest, then given the
  // least-norm change that moves S(u, v) onto its target (section 3.3) over the influence
  // window. So the dent is always centred on the finger, each point's share follows its
  // basis function at the finger (a point the finger leaves goes out with a share near 0,
  // nothing is left behind to trail), and no free point of the support pulls the surface
  // off the probe (they are held: placed, not integrated, until the next press or release).
  clear_hold(true);  // the finger moves on: what it leaves at a share near 0 is put at rest
  const int p_deg = net_.skeleton.degree_u();
  const int q_deg = net_.skeleton.degree_v();
  for (int i = basis.span_u - p_deg; i <= basis.span_u; ++i) {
    for (int j = basis.span_v - q_deg; j <= basis.span_v; ++j) {
      const std::size_t p = idx(i * cols_ + j);
      held_[p] = 1;
      held_list_[held_count_++] = static_cast<std::uint32_t>(p);
      activate(p);
      std::fill_n(&x_[p * kComponents], kComponents, 0.0);
      std::fill_n(&v_[p * kComponents], kComponents, 0.0);
    }
  }
  // Only the support's basis functions are nonzero at (u, v), so with the support at rest
  // the drawn surfaces pass exactly through the rest surfaces there, whatever the rest of
  // the net does: the change needed is the whole target.
  const auto inf = influence_at(net_.skeleton, u, v, options_.influence_u, options_.influence_v);
  for (int ia = 0; ia < inf.rows; ++ia) {
    for (int jb = 0; jb < inf.cols; ++jb) {
      const std::size_t p = idx((inf.i0 + ia) * cols_ + inf.j0 + jb);
      const double w = inf.weight[idx(ia * inf.cols + jb)];
      for (std::size_t c = 0; c < kComponents; ++c) x_[p * kComponents + c] = w * target[c];
    }
  }
  // Every held point is drawn where it now is: in the window displaced, outside it at rest.
  for (std::size_t k = 0; k < held_count_; ++k) write_back(held_list_[k]);
  awake_ = true;
  ++version_;
}

void DeformedBody::set_dynamics(bool on) {
  options_.dynamics = on;
  if (!on && held_count_ == 0 && awake_) put_at_rest();
}

void DeformedBody::release() {
  clear_hold(false);  // the finger lifts: the whole dent springs back on its oscillators
  if (!options_.dynamics) put_at_rest();
}

void DeformedBody::clear_hold(bool snap) {
  for (std::size_t k = 0; k < held_count_; ++k) {
    const std::size_t p = held_list_[k];
    held_[p] = 0;
    // A point the finger slid away from leaves the dent with a share near 0 (its basis
    // function vanishes at the edge of its support): below kSnap it is put at rest at once
    // rather than integrated for tens of milliseconds, so a slide keeps only the support
    // under the finger active, not the trail of points it crossed.
    double largest = 0.0;
    for (int c = 0; c < kComponents; ++c) largest = std::max(largest, std::abs(x_[p * kComponents + idx(c)]));
    if (snap && largest < kSnap) {
      std::fill_n(&x_[p * kComponents], kComponents, 0.0);
      std::fill_n(&v_[p * kComponents], kComponents, 0.0);
      write_back(p);  // it stays in the active list until step() sees it settled
    }
  }
  held_count_ = 0;
}

void DeformedBody::put_at_rest() {
  // Only the active points are displaced: the rest of a refined net is already at rest, so
  // this costs what the dent costs, not what the net does (thousands of points).
  for (const std::uint32_t p : active_) {
    std::fill_n(&x_[std::size_t{p} * kComponents], kComponents, 0.0);
    std::fill_n(&v_[std::size_t{p} * kComponents], kComponents, 0.0);
    is_active_[p] = 0;
    write_back(p);
  }
  active_.clear();
  awake_ = false;
  ++version_;
}

void DeformedBody::activate(std::size_t point) {
  if (is_active_[point] != 0) return;
  is_active_[point] = 1;
  active_.push_back(static_cast<std::uint32_t>(point));  // within the reserved capacity
}

void DeformedBody::rebuild_steps(double dt) {
  for (std::size_t p = 0; p < steps_.size(); ++p) steps_[p] = OscillatorStep::exact(k_[p], b_[p], m_[p], dt);
  step_dt_ = dt;
}

void DeformedBody::step(double dt) {
  if (!awake_ || !(dt > 0.0)) return;
  if (!options_.dynamics) return;  // released points went back at release(); held ones stay
  // A real-time loop measures dt with jitter: rebuilding every point's exact map on each
  // tick would cost more than the integration. The map is rebuilt only when dt moved by
  // more than 1 %; integrating with the previous step length instead is still exact for
  // that length and unconditionally stable, it only shifts the springs' time by <= 1 %.
  if (!(std::abs(dt - step_dt_) <= 0.01 * dt)) rebuild_steps(dt);
  bool moving = false;
  bool any_held = false;
  bool changed = false;
  // Only the points a press displaced are visited (a refined net has thousands; a dent
  // moves a few dozen), and a point leaves the list once it has settled.
  std::size_t kept = 0;
  for (std::size_t a = 0; a < active_.size(); ++a) {
    const std::size_t p = active_[a];
    if (held_[p] != 0) {
      any_held = true;
      active_[kept++] = static_cast<std::uint32_t>(p);
      continue;
    }
    double* x = &x_[p * kComponents];
    double* v = &v_[p * kComponents];
    bool point_moving = false;
    for (int c = 0; c < kComponents; ++c) {
      steps_[p].apply(x[c], v[c]);
      point_moving = point_moving || std::abs(x[c]) >= options_.sleep_displacement ||
                     std::abs(v[c]) >= options_.sleep_velocity;
    }
    // A point that has settled is put exactly at rest: left alone it would decay into
    // subnormal numbers, which are two orders of magnitude slower to compute with, while
    // a long press keeps the body awake.
    if (!point_moving) {
      std::fill_n(x, kComponents, 0.0);
      std::fill_n(v, kComponents, 0.0);
      is_active_[p] = 0;
    } else {
      active_[kept++] = static_cast<std::uint32_t>(p);
    }
    moving = moving || point_moving;
    changed = true;
    write_back(p);
  }
  active_.resize(kept);  // shrinking never allocates
  if (changed) ++version_;  // a static hold changes nothing: nothing to re-tessellate
  if (!any_held && !moving) {
    // At rest within the thresholds: put it exactly at rest and stop integrating.
    const std::uint64_t version = version_;
    put_at_rest();
    version_ = version;  // nothing moved that was not already drawn
  }
}

double DeformedBody::max_displacement() const {
  double m = 0.0;
  for (double x : x_) m = std::max(m, std::abs(x));
  return m;
}

double DeformedBody::energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < k_.size(); ++p) {
    for (int c = 0; c < kComponents; ++c) {
      const double x = x_[p * kComponents + idx(c)];
      const double v = v_[p * kComponents + idx(c)];
      e += 0.5 * (m_[p] * v * v + k_[p] * x * x);
    }
  }
  return e;
}

}  // namespace palpa::deform
