#pragma once
// Scenes like the paper's Table 1 (Corso, Chhugani & Okamura 2002): 1 to 35 breast-like
// domes side by side along x, 12 cm apart, with the paper's body and MAT point counts, and
// the scripted palpation that visits them. Shared by `palpa-cli bench table1` (haptic
// rates) and `palpa --bench` (graphics frame rates), so both measure the same scenes.
#include <array>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/scene/scene.hpp"

namespace palpa::scene {

struct Table1Scene {
  int bodies;
  int mat_points;
  std::vector<std::array<int, 3>> grids;  ///< {count, rows, cols}
  // the paper's row (700 MHz Pentium III): preprocessing s, memory MB, haptic Hz with/without dynamics
  double paper_pre_s, paper_mb, paper_hz_dyn, paper_hz_nodyn;
};

/// The six rows: 1/49, 1/105, 4/213, 10/309, 17/465, 35/927 bodies/MAT points.
const std::vector<Table1Scene>& table1_scenes();

/// The scene as a case file (no tumours): body k is centred at x = 0.12 k m, 10 cm wide,
/// its top contour 3 cm high at the centre.
io::CaseFile make_table1_case(const Table1Scene& spec);

/// Where the scripted finger is at time t (s): it visits the bodies in turn (one per
/// 0.25 s), making small circles (15 mm, 9 rad/s) and pressing 2-14 mm into each.
Vec3 table1_probe(int bodies, double t);

}  // namespace palpa::scene
