#pragma once
// A grayscale image read as a stiffness map (OpenCV; core never sees an image library):
// black is the softest, white the stiffest. The image is taken as seen from above the
// body: its columns run along x (the body's grid rows, u), from left to right, and its
// rows along y (the grid columns, v), from the bottom of the image to the top.
#include <optional>
#include <string>

#include "palpa/author/stiffness_map.hpp"

namespace palpa::ui {

/// Images are shrunk (area averaging) to at most this many pixels per side: far finer than
/// any skeleton grid (<= 256 points), and it keeps a camera photo from costing seconds.
inline constexpr int kMaxStiffnessMapSide = 256;

/// Reads `path` as 8-bit grayscale, shrinks it to kMaxStiffnessMapSide and normalizes it
/// to [0, 1] (value / 255). On failure returns nothing and sets `error` to one line
/// "PATH: REASON".
std::optional<author::StiffnessMap> read_stiffness_image(const std::string& path, std::string& error);

}  // namespace palpa::ui
