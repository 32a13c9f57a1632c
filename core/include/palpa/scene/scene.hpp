#pragma once
// A scene: the fitted bodies of a case with their tumours, and the probe query the
// haptic loop runs against them (the deepest penetration wins; bodies whose bounding
// box cannot contain the probe are skipped without a foot-point search).
#include <optional>
#include <string>
#include <vector>

#include "palpa/contact/column.hpp"
#include "palpa/contact/force.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/mat/layer_stiffness.hpp"

namespace palpa::scene {


/// Axis-aligned box that contains a body: SK's control points (convex hull property)
/// grown by the largest radius control value, which bounds R(u, v).
struct Bounds {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  bool contains(const Vec3& q) const;
};
/// m: how far past its bottom contour a body on a support keeps its wall (the device may
/// press that deep and still meet it). Its probe box is grown by this much.
inline constexpr double kSupportReach = 0.05;

Bounds bounds_of(const mat::MatBody& body);
/// The box Scene::probe culls with: the bounds, and for a body on a support the bounds
/// grown by kSupportReach, so that a probe pressed into the support is never culled.
Bounds probe_box_of(const mat::MatBody& body, const Bounds& bounds);

struct SceneBody {
  mat::MatBody body;
  contact::FootPointSearch search;
  Bounds bounds;     ///< the body itself
  Bounds probe_box;  ///< what the probe query culls with (probe_box_of)
  std::vector<mat::Tumour> tumours;
  /// Calibrated: the normal spring alone (its stiffness came from the tissue's modulus),
  /// whatever ForceOptions::shear says; Paper: the shear springs as ForceOptions::shear says.
  mat::ForceModel force_model = mat::ForceModel::Paper;
  /// A body given by its modulus: kappa of its material, to read the modulus back from the
  /// stiffness at a contact (a rounded finger's force needs it); empty for a body in N/m.
  std::optional<mat::LayerStiffnessTable> layer;
  double poisson = 0.49;
  double stiffening = 0.0;  ///< b of a body given by its modulus (mat::BodyGrid::stiffening)
  /// A body on a support: the axis its skeleton is a graph over, along which a press under
  /// the skeleton is read (contact::column_contact); not usable for a free body.
  contact::PressAxis press_axis{};
};

/// How far a tumour's sphere stays inside `body` (m): the smallest depth of its centre and
/// of 26 points around its surface (the faces, edges and corners of a cube, projected onto
/// the sphere). >= 0 means inside; negative is how far it reaches beyond the surface.
/// Scene::build rejects tumours below 0; randomized placement redraws them.
double tumour_clearance(const mat::MatBody& body, const contact::FootPointSearch& search, const mat::Tumour& tumour);

enum class FootPointMethod { Fast, Bisect };

struct ProbeOptions {
  FootPointMethod method = FootPointMethod::Fast;
  int bisect_levels = 10;
  contact::ForceOptions force{};
  /// Treat successive queries as one probe path (a proxy, in the haptics sense: the contact
  /// keeps the surface it entered through). A press into a free body that goes past the
  /// skeleton keeps being pushed back out of the side it entered (depth R + |PQ|), instead
  /// of flipping to the far surface (docs/model.md, "Pressing past the skeleton"); and a
  /// probe in contact with a body stays with it while it is inside, even where another
  /// body's penetration is deeper, until it leaves and touches again. Off by default, so
  /// that unrelated queries stay independent; the haptic engine and `palpa-cli probe
  /// --path` turn it on. Bodies on a support need no memory: their only touchable side is
  /// the top (top_side_contact), whatever path brought the probe in.
  bool remember_side = false;
};

/// Per-probe memory between queries (warm starts, entry sides), sized once for a scene.
struct ProbeState {
  std::vector<double> u, v;
  std::vector<char> warm;
  std::vector<signed char> entry_side;  ///< +1/-1 while a press is in the body, 0 otherwise
  int held = -1;  ///< the body in contact at the last query of a path, -1 when none
};

struct ProbeResult {
  int body = -1;     ///< index of the body the probe penetrates deepest; -1 when outside all
  int nearest = -1;  ///< index of the searched body with the largest depth (inside or not); -1 if all culled
  contact::Contact contact;  ///< the contact with body `nearest`
  contact::Force force;
  int bodies_tested = 0;  ///< bodies whose foot point was searched (the rest were culled)
};

class Scene {
 public:
  /// Fits every body and places the tumours. Throws io::CaseError naming `source` and the
  /// JSON pointer: a body that cannot be fitted (/bodies/K), a tumour outside its body
  /// (/tumors/K).
  static Scene build(const io::CaseFile& file, const std::string& source, const mat::FitOptions& options = {});

  std::size_t size() const { return bodies_.size(); }
  const SceneBody& body(std::size_t index) const { return bodies_[index]; }
  ProbeState make_state() const;

  /// Resolves the probe against every body; allocation-free given a sized state.
  ProbeResult probe(const Vec3& q, ProbeState& state, const ProbeOptions& options = {}) const;

  /// What presses bodies under the calibrated law (the case's "indenter").
  mat::Indenter indenter() const { return indenter_; }

 private:
  std::vector<SceneBody> bodies_;
  mat::Indenter indenter_ = mat::Indenter::Pad;
};

}  // namespace palpa::scene
