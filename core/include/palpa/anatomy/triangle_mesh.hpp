#pragma once
// A triangulated surface as the import sees it: points and triangles, plain arrays. The
// readers (readers/) fill it from STL, OBJ or PLY files, already in metres.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace palpa::anatomy {

struct TriangleMesh {
  std::vector<std::array<double, 3>> points;         ///< m
  std::vector<std::array<std::int32_t, 3>> triangles;  ///< indices into points
};

/// The most triangles a mesh may have (2^24, about 16.8 million): checked before reading.
inline constexpr std::size_t kMaxTriangles = std::size_t{1} << 24;

}  // namespace palpa::anatomy
