#pragma once
// The case an instructor is editing (instructor mode), headless: the JSON
// document is the source of truth (so a draft can hold a case that does not validate yet
// and show where it is wrong), every edit is undoable, and validate() gives the problems
// with their JSON pointers exactly as palpa-cli validate would.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/author/presets.hpp"
#include "palpa/author/stiffness_map.hpp"
#include "palpa/scripted/tumour_placement.hpp"
#include "palpa/io/case_file.hpp"
#include "palpa/io/thresholds.hpp"

namespace palpa::author {

/// A point picked on a body's top contour, with the outward unit normal there.
struct SurfacePoint {
  std::size_t body = 0;                  ///< index into the case's bodies
  std::array<double, 3> point{};         ///< m
  std::array<double, 3> normal{0, 0, 1}; ///< outward; need not be unit length (normalized)
};

/// What an instructor sets for a tumour besides where it is.
struct TumourSpec {
  double depth = 0.01;       ///< m, of the centre below the picked surface point (along the normal)
  double radius = 0.005;     ///< m
  double stiffness = 2000.0; ///< N/m: a ~100 kPa region under a fingertip (flat punch: docs/case-authoring.md)
  /// Pa; > 0: the tumour is written by its Young's modulus instead of `stiffness` (its body
  /// must give its tissue in Pa too).
  double modulus = 0.0;
  /// With a modulus: its strain stiffening b (E exp(b eps); docs/model.md), 0: none.
  double stiffening = 0.0;
};

/// The exam region as the instructor window edits it: the same rectangle of every body,
/// as shares of its skeleton's parameters (u along x, v along y; 0 one end, 1 the other).
struct ExamExtent {
  std::array<double, 2> u{0.0, 1.0};
  std::array<double, 2> v{0.0, 1.0};
  bool operator==(const ExamExtent&) const = default;
};

/// Approximate memory (bytes) a JSON value holds: its nodes, strings and containers.
std::size_t approx_bytes(const nlohmann::json& value);

class CaseDraft {
 public:
  /// A new case from a preset at `params`.
  explicit CaseDraft(const PresetParams& params = preset_defaults_in_kpa(Preset::Breast));

  /// Reads a case file for editing. The draft keeps a document that parses as JSON even
  /// when it does not validate (validate() then says where). Throws io::CaseError when the
  /// file cannot be read or is not JSON (nothing to edit).
  static CaseDraft load(const std::filesystem::path& path);
  /// A draft of a document (e.g. built by hand or by a test); `source` names it in problems.
  static CaseDraft from_document(nlohmann::json document, std::string source);

  const nlohmann::json& document() const { return doc_; }
  /// The file the draft was loaded from or last saved to (empty for a new case).
  const std::filesystem::path& path() const { return path_; }
  /// How problems name the case: the path, or "untitled" for a new case.
  std::string source() const;

  /// The problems palpa-cli validate would report (structure, fit, tumours inside their
  /// bodies, placement rules that can be drawn); empty when the case is valid.
  std::vector<io::Problem> validate() const;
  /// The validated case. Throws io::CaseError with the problems when it is not valid.
  io::CaseFile valid_case() const;
  /// The case as parsed, without the fit checks; nothing when its structure is invalid.
  std::optional<io::CaseFile> parsed() const;

  /// Writes the case (validated first; throws io::CaseError and writes nothing when it is
  /// invalid) atomically to `path`; the draft then refers to that file and is clean.
  void save(const std::filesystem::path& path);
  /// Edited since it was created, loaded or last saved (undoing back to that state clears it).
  bool dirty() const { return revision_ != saved_revision_; }

  // --- Edits: each is one undo step. Tumour indices are those of the "tumors" array. ---

  /// Replaces the case's bodies by the preset's body and records the parameters (root field
  /// "preset"). Tumours are kept where they are (re-pointed to the new body) and lose their
  /// anchor, a point of the old skin, so that their depth is measured to the new skin; one
  /// that no longer fits shows up in validate(). Throws std::invalid_argument outside the
  /// preset's limits. The old preset's scoring keys (preset_scoring) give way to the new
  /// one's, unless the instructor changed them.
  void apply_preset(const PresetParams& params);
  /// Throws std::invalid_argument (and records nothing) when the document is not an object.
  void set_title(const std::string& title);
  /// Adds a tumour `spec.depth` below `where` along its inward normal; returns its index.
  /// The picked point and normal are kept in the tumour ("anchor", an authoring field
  /// preserved by every tool) so that its depth can be edited later.
  std::size_t add_tumour(const SurfacePoint& where, const TumourSpec& spec);
  /// Moves tumour k under another surface point, keeping its depth, radius and stiffness.
  void move_tumour(std::size_t k, const SurfacePoint& where);
  /// Sets tumour k's depth (below its anchor), radius and stiffness. The centre is rewritten
  /// only when spec.depth differs from spec(k)'s, so that editing the radius or stiffness
  /// leaves it exactly as written.
  void edit_tumour(std::size_t k, const TumourSpec& spec);
  void remove_tumour(std::size_t k);
  /// Sets (or with nothing, removes) tumour k's randomization rule.
  void set_placement(std::size_t k, const std::optional<scripted::Placement>& rule);
  /// Sets body b's stiffness from a map (apply_stiffness_map). Throws std::invalid_argument
  /// for a bad map or range, io::CaseError when the body cannot be read or fitted.
  void apply_stiffness_map(std::size_t b, const StiffnessMap& map, double k_min, double k_max);
  /// Sets body b's tissue modulus from a map (author::apply_modulus_map, Pa), keeping its
  /// Poisson's ratio and force law. Throws std::invalid_argument when body b gives its
  /// tissue in N/m, or as apply_stiffness_map.
  void apply_modulus_map(std::size_t b, const StiffnessMap& map, double e_min, double e_max);

  /// Sets the case's "description" (an empty text removes it).
  void set_description(const std::string& text);
  /// Sets scoring key `key` to `value` (SI, as docs/case-format.md gives it), or with
  /// nothing removes it (the default applies). A bad value shows up in validate().
  void set_scoring(const std::string& key, std::optional<double> value);
  /// Sets the exam region to the same rectangle of every body, or with nothing to the whole
  /// top contour of every body (removes "exam_region").
  void set_exam_region(const std::optional<ExamExtent>& extent);

  // --- Reading back what the editor shows ---

  std::string description() const;
  /// The thresholds the case is scored with: the defaults overridden by its "scoring" and
  /// "exam_region" (io::thresholds_from_case; a bad value leaves its default).
  io::Thresholds thresholds() const;
  /// Whether the exam region is the whole surface (no "exam_region"), one rectangle of every
  /// body (exam_extent()), or something else the window does not edit (kept as written).
  enum class RegionKind { Whole, Extent, Custom };
  RegionKind exam_region_kind() const;
  std::optional<ExamExtent> exam_extent() const;

  std::string title() const;
  /// The preset the bodies were made from, if the document records one.
  std::optional<PresetParams> preset() const;
  /// What the preset controls start from: the preset the bodies were made from or, for a
  /// case not made from one, the breast preset sized and filled like its first body (the
  /// span of its medial points in x and y, twice its largest radius, the mean of its
  /// modulus or stiffness and its stiffening), each clamped into the breast preset's limits.
  PresetParams preset_or_nearest() const;
  std::size_t tumour_count() const;
  /// Every body gives its tissue by its modulus ("modulus", Pa): the editor speaks kPa.
  /// False for a case without bodies.
  bool tissue_in_pa() const;
  /// Tumour k's body, centre, radius and stiffness as written (no validation).
  std::optional<mat::Tumour> tumour(std::size_t k) const;
  /// Tumour k's anchor: as recorded by add_tumour/move_tumour, or else the point of the
  /// body's top contour straight above its centre (+z, fitted), when there is one.
  std::optional<SurfacePoint> anchor(std::size_t k) const;
  /// depth (distance from the anchor), radius and stiffness or modulus of tumour k.
  std::optional<TumourSpec> spec(std::size_t k) const;
  std::optional<scripted::Placement> placement(std::size_t k) const;
  /// For each tumour, the depths below the skin (m, of its centre) its randomization rule
  /// can give it: the rule's depth shares of the local thickness over its (u, v) rectangle
  /// (sampled on a 9 x 9 grid), as scripted::place_tumours draws them; nothing for a tumour
  /// without a rule, or when the bodies cannot be fitted.
  std::vector<std::optional<std::array<double, 2>>> random_depth_ranges() const;

  // --- Undo ---
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  /// Restores the document before the last edit; false when there is none.
  bool undo();
  bool redo();
  /// How much history undo keeps: the oldest steps are dropped beyond either limit (the
  /// newest step is always kept, so the last edit can be undone).
  struct UndoLimits {
    std::size_t steps = 200;
    std::size_t bytes = std::size_t{256} << 20;  ///< approximate memory of the kept documents (undo and redo)
  };
  void set_undo_limits(const UndoLimits& limits);
  const UndoLimits& undo_limits() const { return limits_; }
  /// The approximate memory the undo and redo documents hold (approx_bytes of each).
  std::size_t history_bytes() const { return history_bytes_; }

 private:
  struct State {
    nlohmann::json doc;
    std::uint64_t revision = 0;
    std::size_t bytes = 0;  // approx_bytes(doc)
  };
  /// Records the current document for undo and starts a new revision.
  void begin_edit();
  /// Drops the oldest undo steps beyond the limits.
  void trim_history();
  State take_current();
  nlohmann::json& tumour_json(std::size_t k);  // throws std::out_of_range
  void swap_preset_scoring(const nlohmann::json& made);
  /// The id of body b; throws std::out_of_range when there is none (never inserts).
  nlohmann::json body_id(std::size_t b) const;

  nlohmann::json doc_;
  std::filesystem::path path_;
  std::string source_ = "untitled";
  std::vector<State> undo_, redo_;
  UndoLimits limits_;
  std::size_t history_bytes_ = 0;
  std::uint64_t revision_ = 0, next_revision_ = 1, saved_revision_ = 0;
};

}  // namespace palpa::author
