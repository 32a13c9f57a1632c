#pragma once
// A scripted trainee: a Device that plans and performs a palpation exam on the top contour
// of a scene's bodies (vertical strips, a press cycle at each spot, sliding from spot to
// spot in contact along a strip) and finds tumours only
// from the force it feels through write_force(), as a person would: it never sees the
// case's ground truth. Three styles reproduce the exams the scorer must tell apart
// (docs/scoring.md, its sources): a thorough expert (MammaCare vertical strips, three
// pressures), a sloppy trainee (wide strips, a skipped strip, medium pressure, false
// marks) and a light one (full coverage, light pressure only).
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "palpa/engine/device.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/session/session.hpp"
#include "palpa/vec3.hpp"

namespace palpa::scripted {


enum class Style : std::uint8_t { Expert, Sloppy, Light };

/// "expert", "sloppy", "light".
std::string_view to_string(Style style);
std::optional<Style> style_from_string(std::string_view name);

/// A rectangle of one body's skeleton parameters to examine.
struct ExamRect {
  std::size_t body = 0;
  double u0 = 0.0, u1 = 1.0;
  double v0 = 0.0, v1 = 1.0;
};

/// The exam region: the whole top contour of every body of `scene`.
std::vector<ExamRect> whole_top_contours(const scene::Scene& scene);

/// How a style palpates (SI units; depths as fractions of the local thickness 2R).
struct StyleParameters {
  double strip_spacing = 0.013;  ///< m, between strips (arc length across them)
  double spot_step = 0.007;      ///< m, between spots along a strip
  int skip_every = 0;            ///< skip strip k when k % skip_every == skip_every - 1 (0: none)
  /// Pressure levels, increasing. The deep one stops just past half the thickness, the
  /// default deep band's edge (a person aims past a threshold, and a press planned exactly
  /// on it would score as medium wherever round-off in the thickness falls below it); much
  /// deeper the tissue alone pushes back hard (tissue stiffens), so a tumour stands out less
  /// against the force limit.
  std::array<double, 3> levels{0.10, 0.30, 0.52};
  int level_count = 3;
  /// N: a press stops going deeper when the felt |F| reaches this and holds the
  /// indentation reached (closed loop on the force felt), as a real examiner limits force.
  double force_limit = 15.0;
  /// Keep contact along a strip (MammaCare: the pads slide along the strip without
  /// lifting): between spots of one strip, slide at `slide_level`; lift only between strips.
  bool slide = true;
  double slide_level = 0.10;     ///< fraction of the local thickness while sliding
  double lift = 0.004;           ///< m, above the surface between strips (every spot when not sliding)
  double move_speed = 0.07;      ///< m/s, gliding between spots
  double press_speed = 0.2;      ///< m/s, pressing in and releasing
  double hold = 0.04;            ///< s, held at each level before the force is read
  double neighbourhood = 0.025;  ///< m, spots compared with one another
  double suspicion_ratio = 1.3;  ///< stiffer than the neighbourhood's median by this: suspicious
  double group_distance = 0.02;  ///< m, suspicious spots closer than this are one finding
  /// Re-palpating a finding presses this much deeper than the deep level and up to this
  /// much more force than the search presses there felt, never over force_limit.
  double repalpate_factor = 1.15;
  double confirm_ratio = 1.2;    ///< a re-palpation this much stiffer than the neighbourhood: mark
  /// The same two thresholds for bodies whose tissue is given in Pa (the calibrated law).
  /// Plain tissue there varies only with its thickness over the rigid base, which the
  /// trainee discounts (it knows tissue over the chest wall feels firmer: each spot's
  /// stiffness is divided by the layer's factor for its thickness, mat::LayerStiffnessTable),
  /// so it can notice what a person can: about 20 % firmer (the compliance JND; docs/user-guide.md,
  /// "Cases in kPa"; 1.18 stays above the 16 % that the layer's shape still leaves on a plain
  /// breast). The paper's springs vary by tens of per cent across a plain body with its
  /// shape, hence the higher thresholds above for bodies in N/m.
  /// m: the neighbourhood in tissue given in Pa. A mass there lifts the force up to
  /// 2 (a + 0.24 s) beside it (docs/model.md, "Beside the pad's axis": 29 mm for one 30 mm
  /// deep), so the expert compares a spot with the tissue around that reach, as an
  /// examiner compares with the rest of the breast rather than the mass's own rim.
  double tissue_neighbourhood = 0.04;
  double tissue_suspicion_ratio = 1.20;
  double tissue_confirm_ratio = 1.18;
  double min_thickness = 0.004;  ///< m: thinner tissue holds no palpable mass; not judged
  int false_marks_min = 0;       ///< marks this many to ...
  int false_marks_max = 0;       ///< ... this many spots (drawn from the seed) where it felt nothing
  double false_mark_clearance = 0.03;  ///< m, such marks keep this far from anything felt and each other
  double pad_radius = 7.5e-3;    ///< m, finger pad (coverage)
};

StyleParameters parameters_for(Style style);

/// A planned press spot.
struct Spot {
  std::size_t body = 0;
  double u = 0.0, v = 0.0;
  Vec3 top = Vec3::Zero();     ///< m, top-contour point
  Vec3 normal = Vec3::UnitZ();
  double thickness = 0.0;      ///< m, 2R
  int strip = 0;
};

class ScriptedTrainee final : public engine::Device {
 public:
  /// Plans the whole exam (and sizes every buffer) here; read and write allocate nothing.
  /// The scene must outlive the trainee.
  ScriptedTrainee(const scene::Scene& scene, const std::vector<ExamRect>& region, Style style, std::uint64_t seed);
  ScriptedTrainee(const scene::Scene& scene, const std::vector<ExamRect>& region, Style style,
                  const StyleParameters& parameters, std::uint64_t seed);

  const engine::DeviceCapabilities& capabilities() const override { return caps_; }
  /// The probe position of the plan at t (t must not decrease between calls).
  engine::DeviceStatus read(double t, engine::DevicePose& pose) noexcept override;
  /// The force the trainee feels; the last one is what it judges a press by.
  engine::DeviceStatus write_force(const Vec3& force) noexcept override;

  /// The next event it produced (Mark, with id from 1 and the probe position on the
  /// surface), oldest first; false when none is waiting. Poll after every tick.
  bool pop_event(session::Event& event) noexcept;

  /// True once the whole plan (with re-palpations and marks) has been performed.
  bool finished() const { return finished_; }
  /// When it finished (s); meaningful once finished().
  double finish_time() const { return finish_time_; }
  /// The scan alone (no re-palpation or marking detours), s.
  double scan_duration() const { return scan_duration_; }

  Style style() const { return style_; }
  const StyleParameters& parameters() const { return params_; }
  const std::vector<Spot>& spots() const { return spots_; }
  /// Effective stiffness |F| / indentation measured at each spot's deepest press (N/m),
  /// 0 until pressed; the indentation is the one actually held (force-limited presses
  /// hold less than planned).
  const std::vector<double>& measured_stiffness() const { return stiffness_; }
  /// The indentation held at each spot's deepest press (m) and |F| felt there (N); 0 until pressed.
  const std::vector<double>& held_indentation() const { return held_; }
  const std::vector<double>& pressed_force() const { return pressed_force_; }
  /// When each spot's deepest press was judged (s); -1 until pressed.
  const std::vector<double>& measure_times() const { return measure_time_; }
  /// The deepest planned indentation as a fraction of the local thickness.
  double max_depth_fraction() const;
  const Vec3& last_force() const { return force_; }

 private:
  enum class Action : std::uint8_t { None, Measure, StripEnd, Repalpate, MarkFinding, MarkFalse, End };
  struct Waypoint {
    Vec3 position = Vec3::Zero();  ///< as planned; a press may hold shallower
    double duration = 0.0;  ///< s, from the previous waypoint
    Action action = Action::None;
    int index = -1;  ///< spot, strip or finding
    /// A press: `position` lies `indentation` (m) below the pressed top-contour point along
    /// `normal`, and the indentation is capped where |F| reached `force_limit`.
    bool press = false;
    double indentation = 0.0;
    Vec3 normal = Vec3::Zero();
    double force_limit = 0.0;  ///< N
    int spot = -1;             ///< the search spot pressed (its force-depth curve is recorded)
  };
  struct Finding {
    std::size_t body = 0;
    int grid = 0;            ///< the deepest depth grid index the neighbourhood was judged at
    double u = 0.0, v = 0.0;
    Vec3 top = Vec3::Zero();
    double thickness = 0.0;  ///< m, 2R
    double reference = 0.0;  ///< N/m: the neighbourhood's median stiffness at the re-palpation's depth
    double felt = 0.0;       ///< N/m: measured at the re-palpation
    bool marked = false;
  };

  void plan(const std::vector<ExamRect>& region);
  void plan_rect(const ExamRect& rect, int& strip);
  /// A press waypoint at `spot` (top, normal) pressed `indentation` deep.
  static Waypoint press_to(const Vec3& top, const Vec3& normal, double indentation, double duration,
                           double force_limit, Action action = Action::None, int index = -1);
  /// The press cycle at a spot from `from_depth` (m below its top, 0: touching) through the
  /// levels, ending `to_depth` deep.
  void add_press(std::vector<Waypoint>& out, const Spot& spot, int spot_index, double from_depth,
                 double to_depth) const;
  /// In contact from one spot of a strip to the next, at the slide level.
  void add_slide(std::vector<Waypoint>& out, const Spot& from, const Spot& to) const;
  void add_transit(std::vector<Waypoint>& out, std::size_t body, double u0, double v0, double u1, double v1,
                   const Vec3& from) const;
  /// A glide from a spot to another, lifted; over the bodies when it changes body.
  void add_glide(std::vector<Waypoint>& out, std::size_t from_body, double u0, double v0, std::size_t to_body,
                 double u1, double v1, const Vec3& from) const;
  /// Where the probe goes for `w`: a press's position with the indentation capped.
  Vec3 target_of(const Waypoint& w) const noexcept;
  /// The force loop of a press: caps the indentation where |F| reached the limit, and
  /// records the search spot's force-depth curve.
  void regulate(const Waypoint& w) noexcept;
  /// The spot's stiffness |F| / indentation at depth grid point k, 0 when not reached.
  double stiffness_at(std::size_t spot, int k) const noexcept;
  /// The median stiffness at grid point k of the spots around `top` on `body` (not
  /// `exclude`), 0 with fewer than three.
  double neighbourhood_median(std::size_t body, const Vec3& top, int k, std::size_t exclude) noexcept;
  /// The deepest depth grid point a spot's press reached, -1 for none.
  int deepest_grid(std::size_t spot) const noexcept;
  void complete(const Waypoint& w, double t) noexcept;
  void judge_strip(int strip, bool provisional) noexcept;
  void find_groups(std::size_t at) noexcept;
  void add_false_marks() noexcept;
  void push_mark(double t, const Vec3& position) noexcept;
  bool detour_room(std::size_t waypoints) const { return detour_.size() + waypoints <= detour_.capacity(); }

  const scene::Scene* scene_;
  Style style_;
  StyleParameters params_;
  engine::DeviceCapabilities caps_;
  std::uint64_t rng_state_;

  std::vector<Spot> spots_;
  std::vector<Waypoint> scan_;
  std::vector<int> strip_first_;  ///< first spot of each strip, plus one past the end
  double scan_duration_ = 0.0;

  // Execution: the scan, interrupted by detours (re-palpations, marks) planned on the fly
  // into preallocated buffers.
  std::vector<Waypoint> detour_;
  std::size_t next_scan_ = 0;
  std::size_t next_detour_ = 0;
  bool in_detour_ = false;
  Vec3 from_ = Vec3::Zero();
  double segment_start_ = 0.0;
  bool finished_ = false;
  double finish_time_ = 0.0;
  Vec3 force_ = Vec3::Zero();
  Vec3 last_pose_ = Vec3::Zero();  ///< the position last commanded (what force_ was felt at)
  double previous_felt_ = 0.0;     ///< N, |F| felt the tick before
  double cap_ = 0.0;  ///< m, the current press's indentation cap (infinite until |F| reaches the limit)

  std::vector<double> stiffness_;
  std::vector<double> held_;
  std::vector<double> pressed_force_;
  std::vector<double> measure_time_;
  // Each search press's force-depth curve: |F| at depth fractions k * kDepthStep of the
  // local thickness (0: not reached), so spots are compared at the same depth (a
  // force-limited press over a mass holds shallower than its neighbours).
  static constexpr int kDepthGrid = 16;
  static constexpr double kDepthStep = 0.05;
  std::vector<double> curve_;
  int curve_spot_ = -1;
  double curve_fraction_ = 0.0, curve_force_ = 0.0;  ///< last point fed
  std::vector<double> ratio_;       ///< stiffness / neighbourhood median; 0 until judged
  /// Per spot: N/m per Pa of its layer (bodies in Pa) or 1 (bodies in N/m); stiffnesses are
  /// compared divided by it, so a thinner layer's firmness is not taken for a mass.
  std::vector<double> layer_factor_;
  double layer_factor(std::size_t body, double thickness) const noexcept;
  bool in_pa(std::size_t body) const noexcept;
  // Per spot: nothing felt, suspicious, suspicious on a provisional judgement (may join a
  // finding, cannot start one), taken into a finding.
  enum : char { kPlain = 0, kSuspicious = 1, kMayJoin = 2, kTaken = 3 };
  std::vector<char> suspicious_;
  std::vector<double> scratch_;     ///< median buffer
  std::vector<int> group_;          ///< grouping buffer
  std::vector<Finding> findings_;
  std::vector<session::Event> events_;
  std::size_t events_read_ = 0;
  std::int64_t next_mark_ = 1;
};

}  // namespace palpa::scripted
