// Re-tessellating for display must not allocate once the meshes have their capacity: the
// GUI thread does it every frame for every body that moved. Run with a counting global
// operator new (this test binary only).
#include <gtest/gtest.h>


#include <atomic>
#include <cstdlib>
#include <new>

#include "palpa/contact/contact.hpp"
#include "palpa/contact/foot_point.hpp"
#include "palpa/deform/deformed_body.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/render/tessellation.hpp"
#include "../support/counting_allocator.hpp"


namespace palpa::render {
namespace {

/// Presses along a path over the body, lets it spring back between presses, and
/// re-tessellates after every change; returns the allocations made inside update().
long press_and_tessellate(const mat::MatBody& rest, deform::DeformedBody& body, BodyMeshes& meshes,
                          const TessellationOptions& o, int& updates) {
  const contact::FootPointSearch search(rest.skeleton());
  long inside_update = 0;
  auto update = [&] {
    const long before = palpa::test::allocations();
    if (meshes.update(body, o)) ++updates;
    inside_update += palpa::test::allocations() - before;
  };
  update();
  for (int k = 0; k < 40; ++k) {
    const double t = 0.15 * k;
    const double x = 0.04 * std::sin(t);
    const double y = 0.05 * std::cos(0.7 * t);
    // 6 mm below the top surface over (x, y): find the surface height by its foot point.
    const palpa::Vec3 above(x, y, 0.2);
    const auto foot = search.closest(rest.skeleton(), above);
    const auto c0 = contact::make_contact(rest, foot, above);
    const palpa::Vec3 surface = foot.point + c0.radius * c0.outward;
    const palpa::Vec3 q = surface - 0.006 * c0.outward;
    const auto c = contact::make_contact(rest, search.closest(rest.skeleton(), q), q);
    if (c.inside) body.press(c, q);
    update();
    update();  // unchanged: nothing to do
    if (k % 4 == 3) {
      body.release();
      for (int s = 0; s < 5; ++s) {
        body.step(1e-3);
        update();
      }
    }
  }
  return inside_update;
}

TEST(TessellationRealTime, ReTessellatingChangedBodiesAllocatesNothingOnceSized) {
  const auto rest = mat::MatBody::fit(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json").bodies.at(0));
  const TessellationOptions o;
  BodyMeshes meshes;
  int updates = 0;
  {
    deform::DeformedBody warm_up(rest);
    press_and_tessellate(rest, warm_up, meshes, o, updates);  // sizes the meshes
  }
  // The same presses on a fresh body: the same grids, so the storage is reused.
  deform::DeformedBody body(rest);
  updates = 0;
  const long allocations = press_and_tessellate(rest, body, meshes, o, updates);
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(updates, 40);  // it did re-tessellate (at least once per press)
  EXPECT_GT(meshes.top().triangle_count(), 0U);

  // A coarser grid fits in the storage of a finer one.
  Mesh m;
  TessellationOptions fine;
  fine.tolerance = 1e-5;
  tessellate(rest.top(), fine, false, m);
  const long before = palpa::test::allocations();
  tessellate(rest.top(), o, false, m);
  tessellate(rest.bottom(), o, true, m);
  tessellate(rest.top(), fine, false, m);
  EXPECT_EQ(palpa::test::allocations() - before, 0);

  // The counter does see allocations: a fresh mesh allocates.
  Mesh fresh;
  const long control = palpa::test::allocations();
  tessellate(rest.top(), o, false, fresh);
  EXPECT_GT(palpa::test::allocations(), control);
}

}  // namespace
}  // namespace palpa::render
