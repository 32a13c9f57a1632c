#pragma once
// The authored description of one body: the discretized medial axis transform of the
// paper's section 2.1 (skeleton points on a regular grid, sphere radii, material values).
#include <array>
#include <string>
#include <vector>

namespace palpa::mat {

/// What a body rests on (docs/model.md, "Bodies on a support"). A breast lies on the chest
/// wall, a prostate on the pelvis, a skin patch on a table: their bottom contour rests on a
/// rigid support that a finger can neither touch nor pass, so only the top contour is
/// touchable. A free body (a test geometry, an organ held in the air) has two touchable sides.
enum class Support { Free, Bottom };
const char* to_string(Support support);

/// The force law a body's tissue follows (docs/model.md, section 3). Paper: the normal
/// spring and the four shear springs of the paper's section 3.4, with the stiffness as
/// authored in N/m. Calibrated: the normal spring alone, its stiffness derived from the
/// tissue's Young's modulus by contact mechanics (layer_stiffness.hpp), which stays within
/// a few per cent of finite-element tissue where the shear springs overshoot it.
enum class ForceModel { Paper, Calibrated };
const char* to_string(ForceModel model);

/// What presses the tissue under the calibrated law (docs/model.md, "A rounded finger"):
/// a fingertip pad flattened against the skin (a flat punch of 7.5 mm radius, the default:
/// a pad flattens at clinical forces) or a rounded finger (a sphere of 8 mm radius, whose
/// force grows like depth^1.5 at first). The paper's law has springs, not an indenter.
enum class Indenter { Pad, Finger };
const char* to_string(Indenter indenter);

struct BodyGrid {
  std::string id;
  Support support = Support::Free;
  int rows = 0;  ///< points along u
  int cols = 0;  ///< points along v
  /// Skeleton points (m), row-major: point (i, j) at index i*cols + j.
  std::vector<std::array<double, 3>> medial;
  std::vector<double> radius;     ///< m, one per point; 0 on the grid boundary
  std::vector<double> stiffness;  ///< N/m; derived from `modulus` when the body gives that
  std::vector<double> modulus;    ///< Pa, Young's modulus; empty: the body is authored in N/m
  double poisson = 0.49;          ///< Poisson's ratio of a body given by `modulus`
  /// b in E_t(eps) = E exp(b eps): strain stiffening of a body given by `modulus`
  /// (docs/model.md, "Strain stiffening"); 0: the linear layer.
  double stiffening = 0.0;
  ForceModel force_model = ForceModel::Paper;
  std::vector<double> damping;    ///< N s/m; empty: the default damping ratio applies
  std::vector<double> mass;       ///< kg; empty: the default mass applies

  std::size_t point_count() const { return medial.size(); }
};

/// Values used where a case leaves damping or mass out. Each skeleton point is a
/// mass-spring-damper (paper section 3.2): 1 g per point and a damping ratio of 0.7
/// (b = 2 * 0.7 * sqrt(k m)) let a released surface settle quickly with little overshoot.
struct MaterialDefaults {
  double mass = 1e-3;          ///< kg per skeleton point
  double damping_ratio = 0.7;  ///< zeta in b = 2 zeta sqrt(k m)
};

}  // namespace palpa::mat
