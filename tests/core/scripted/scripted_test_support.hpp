#pragma once
// Shared by the scripted-exercise tests (scripted_*_test.cpp): the bundled default case and
// geometry the tests compute themselves from the fitted skeleton (not through core/scripted).
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "palpa/io/case_file.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/vec3.hpp"

namespace palpa::scripted_test {

inline io::CaseFile default_case() { return io::load_case(std::string(PALPA_SOURCE_DIR) + "/data/cases/default.json"); }

struct Column {
  double u = 0.0, v = 0.0;
  Vec3 skeleton = Vec3::Zero();
  double radius = 0.0;
  Vec3 normal = Vec3::UnitZ();
  Vec3 top() const { return skeleton + radius * normal; }
};

inline Column column_at(const mat::MatBody& body, double u, double v) {
  Column c;
  c.u = u;
  c.v = v;
  double s[mat::kRadius + 1];
  body.skeleton().evaluate(u, v, s, mat::kRadius + 1);
  c.skeleton = Vec3(s[0], s[1], s[2]);
  c.radius = s[mat::kRadius];
  double n[3];
  mat::skeleton_normal(body.skeleton(), u, v, n);
  c.normal = Vec3(n[0], n[1], n[2]);
  return c;
}

/// The skeleton column through a point (its foot point's parameters).
inline Column column_through(const scene::SceneBody& body, const Vec3& q) {
  const auto foot = body.search.closest(body.body.skeleton(), q);
  return column_at(body.body, foot.u, foot.v);
}

inline Vec3 centre_of(const mat::Tumour& t) { return {t.center[0], t.center[1], t.center[2]}; }

}  // namespace palpa::scripted_test
