// Random probes everywhere around curved bodies, including the hard places (exactly on the
// skeleton, on its boundary and corners, near the focal distance, tiny offsets, far away),
// cold and warm: no truth but physical properties that must always hold (finite results,
// (u, v) in the box, depth at most the radius, a unit outward, forces capped and zero
// outside).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "contact_test_support.hpp"

namespace palpa::contact {
namespace {

using namespace contact_test;

// ======================================================================================
// Stress: random probes everywhere around a curved body, including the hard places
// (exactly on the skeleton, on its boundary and corners, near the focal distance, far
// away). 1e5 probes (1e4 in debug builds); 1e7 with PALPA_LONG_TESTS=1.

TEST(Stress, RandomProbesGiveFiniteResultsCappedForcesAndDepthAtMostTheRadius) {
  const char* long_tests = std::getenv("PALPA_LONG_TESTS");
  const long count = long_tests != nullptr && std::string(long_tests) == "1" ? 10'000'000 : 10'000L * kLoopScale;
  const MatBody stiff = MatBody::fit(saddle_grid(11, 100.0));
  const MatBody* bodies[] = {&saddle(), &stiff, &cylinder()};
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  long failures = 0;
  const auto fail = [&](const std::string& what, const Vec3& q) {
    if (++failures <= 10) ADD_FAILURE() << what << " at probe (" << q.transpose() << ")";
  };
  for (const MatBody* body : bodies) {
    const FootPointSearch search(body->skeleton());
    const Vec3 centre = sk_point(body->skeleton(), 0.5, 0.5);
    const Vec3 p_mid = centre + 0.3 * sk_at(body->skeleton(), 0.5, 0.5)[mat::kRadius] * sk_normal(body->skeleton(), 0.5, 0.5);
    const std::vector<mat::Tumour> tumours{{body->id(), {p_mid.x(), p_mid.y(), p_mid.z()}, 0.003, 3000.0}};
    ForceOptions options;
    FootPoint warm = search.closest(body->skeleton(), centre);
    for (long n = 0; n < count / 3; ++n) {
      Vec3 q;
      const double u = unit(rng);
      const double v = unit(rng);
      switch (n % 6) {
        case 0:  // anywhere in a box around the body
          q = centre + Vec3(0.15 * (2 * unit(rng) - 1), 0.15 * (2 * unit(rng) - 1), 0.15 * (2 * unit(rng) - 1));
          break;
        case 1:  // exactly on the skeleton (to round-off)
          q = sk_point(body->skeleton(), u, v);
          break;
        case 2:  // on the boundary or a corner of the parameter domain, a little off
          q = sk_point(body->skeleton(), std::round(u), n % 12 == 2 ? std::round(v) : v) +
              1e-3 * unit(rng) * Vec3(gauss(rng), gauss(rng), gauss(rng));
          break;
        case 3:  // inside, near the surface
          q = sk_point(body->skeleton(), u, v) + (2 * unit(rng) - 1) * sk_at(body->skeleton(), u, v)[mat::kRadius] *
                                                      sk_normal(body->skeleton(), u, v);
          break;
        case 4:  // a few cm off the skeleton along its normal (focal distances)
          q = sk_point(body->skeleton(), u, v) + 0.1 * (2 * unit(rng) - 1) * sk_normal(body->skeleton(), u, v);
          break;
        default:  // tiny offsets around the skeleton (|PQ| ~ 1e-300 .. 1e-6)
          q = sk_point(body->skeleton(), u, v) +
              std::pow(10.0, -6.0 - 294.0 * unit(rng)) * Vec3(gauss(rng), gauss(rng), gauss(rng));
          break;
      }
      const bool use_warm = n % 2 == 1;
      const FootPoint f = use_warm ? search.closest_from(body->skeleton(), q, warm.u, warm.v)
                                   : search.closest(body->skeleton(), q);
      warm = f;
      if (!(f.u >= 0.0 && f.u <= 1.0 && f.v >= 0.0 && f.v <= 1.0)) fail("(u, v) outside [0, 1]^2", q);
      if (!finite(f.point) || !finite(f.su) || !finite(f.sv) || !std::isfinite(f.distance) || f.distance < 0.0)
        fail("foot point not finite", q);
      const Contact c = make_contact(*body, f, q);
      if (!std::isfinite(c.depth) || !std::isfinite(c.radius) || !std::isfinite(c.stiffness) || !finite(c.outward))
        fail("contact not finite", q);
      if (!(c.depth <= c.radius)) fail("depth " + std::to_string(c.depth) + " > radius", q);
      if (std::abs(c.outward.norm() - 1.0) > 1e-9) fail("outward not a unit vector", q);
      if (c.inside != (c.depth >= 0.0)) fail("inside != (depth >= 0)", q);
      if (c.radius < 0.0 || c.stiffness < 0.0) fail("negative radius or stiffness", q);
      const Force force = contact_force(*body, c, q, tumours, options);
      if (!finite(force.total) || !finite(force.normal) || !finite(force.shear) || !finite(force.tumour))
        fail("force not finite", q);
      if (force.total.norm() > options.max_force * (1.0 + 1e-12))
        fail("|F| = " + std::to_string(force.total.norm()) + " above the cap", q);
      if (!c.inside && force.total != Vec3::Zero()) fail("force outside", q);
    }
  }
  EXPECT_EQ(failures, 0);
}

}  // namespace
}  // namespace palpa::contact
