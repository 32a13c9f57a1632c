#pragma once
// Palpa's one 3-vector: palpa::Vec3 (Eigen) for geometry in the core and above, and the
// trivially copyable palpa::Array3 that samples, snapshots and files hold (a ring buffer
// copies them with memcpy; Eigen types need not be trivially copyable), with explicit
// conversions between the two. Units are those of the quantity (m, N).
#include <array>

#include <Eigen/Core>

namespace palpa {

using Vec3 = Eigen::Vector3d;
using Array3 = std::array<double, 3>;

inline Array3 to_array(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 to_vec3(const Array3& a) { return {a[0], a[1], a[2]}; }

}  // namespace palpa
