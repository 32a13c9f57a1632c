#pragma once
// Scores a recorded session against the case's hidden ground truth (docs/scoring.md):
// sensitivity, false positives, localization error, coverage and deep coverage of the exam
// region, pressure levels, the palpate/search force ratio, the search pattern, duration,
// peak force and safety; pass/fail by gates and weighted sub-scores for feedback.
// Headless: no GUI, no image code (maps are plain grids the reports draw).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "palpa/io/thresholds.hpp"
#include "palpa/session/session.hpp"
#include "palpa/session/session_reader.hpp"

namespace palpa::score {

// The thresholds are read with the case (io/thresholds.hpp); scoring names them as its own.
using io::RegionPart;
using io::Thresholds;
using io::thresholds_from_case;
using io::to_json;

struct TumourResult {
  std::string body;
  std::array<double, 3> center{};  ///< m
  double radius = 0.0;             ///< m
  bool detectable = true;          ///< counts for the sensitivity gate
  bool found = false;
  std::int64_t mark = -1;          ///< id of the mark that found it
  double localization_error_mm = 0.0;  ///< when found: mark to tumour centre over the top contour
};

struct MarkResult {
  std::int64_t id = -1;
  double t = 0.0;
  std::array<double, 3> position{};
  int tumour = -1;          ///< index into Score::tumours it hit, -1: none
  bool duplicate = false;   ///< within reach of a tumour already found by another mark
  double nearest_mm = 0.0;  ///< distance to the nearest tumour over the top contour
};

struct PressureLevels {
  double light_s = 0.0, medium_s = 0.0, deep_s = 0.0;  ///< contact time at each level
};

/// Search-pattern classes after Azari et al. 2015 (docs/scoring.md, "Search pattern");
/// None: no contact at all.
enum class PatternKind { None, Sporadic, Localized, Thorough, Efficient };

/// The class's name in files and reports: "none", "sporadic", "localized", "thorough",
/// "efficient".
std::string to_string(PatternKind kind);

/// Search pattern after Azari et al. 2015: sporadic, localized, thorough or efficient.
struct SearchPattern {
  PatternKind kind = PatternKind::None;
  double path_length_m = 0.0;    ///< length of the contact path over the top contour
  double strip_fraction = 0.0;   ///< share of the path along the dominant strip direction
  double strip_spacing_mm = 0.0; ///< median spacing between neighbouring strips (0: no strips)
  double revisit_fraction = 0.0; ///< share of the path over ground already covered earlier
  double efficiency = 0.0;       ///< area covered / (path length * pad diameter), 0..1
};

/// Pass/fail criterion: all gates must pass.
struct Gate {
  std::string name;  ///< "sensitivity" | "false_positives" | "coverage" | "deep_coverage" | "safety"
  bool passed = false;
  double value = 0.0;
  double threshold = 0.0;
  std::string message;  ///< one readable sentence for the trainee
};

struct SubScore {
  std::string name;
  double value = 0.0;   ///< 0..1
  double weight = 0.0;  ///< normalized, the weights sum to 1
};

/// Per-body map of the exam over the top contour, on a (u, v) grid of cells.
struct BodyMap {
  std::string body;
  int rows = 0, cols = 0;       ///< cells along u and v
  std::vector<double> area;     ///< m^2 per cell (0 outside the exam region), rows*cols row-major
  std::vector<std::array<float, 3>> center;  ///< m: the top-contour point at each cell's centre (for top-down maps)
  std::vector<std::uint8_t> level;  ///< deepest pressure reached per cell: 0 untouched, 1 light, 2 medium, 3 deep
  std::vector<float> dwell_s;   ///< contact time attributed to each cell
  std::vector<float> peak_force_n;  ///< largest force while the cell was under the pad
};

struct Score {
  bool passed = false;
  double score = 0.0;  ///< weighted sub-scores, 0..1
  double sensitivity = 0.0;  ///< detectable tumours found / detectable tumours (1 when there are none)
  int false_positives = 0;
  std::vector<double> localization_error_mm;  ///< per found tumour, in tumour order
  double coverage = 0.0;       ///< 0..1 of the exam region's area
  double deep_coverage = 0.0;  ///< 0..1 reached at deep pressure
  double duration_s = 0.0;     ///< active exam time: start to end (or last sample) minus pauses
  double contact_time_s = 0.0;
  double peak_force_n = 0.0;
  bool safe = true;
  bool short_exam = false;     ///< duration below the threshold (flag)
  double palpate_search_ratio = 0.0;  ///< mean force near marks / elsewhere in contact; 0 when undefined
  PressureLevels pressure;
  SearchPattern pattern;
  std::vector<Gate> gates;
  std::vector<SubScore> subscores;
  std::vector<TumourResult> tumours;
  std::vector<MarkResult> marks;
  std::vector<BodyMap> maps;
  std::vector<std::string> notes;  ///< e.g. "session incomplete: scored up to t = 12.3 s"
  Thresholds thresholds;
  bool complete = true;
  /// The trainee gave the attempt up (session::is_abandoned): no exam, passed is false and
  /// reports say "abandoned", not "failed".
  bool abandoned = false;
  std::uint64_t samples = 0;
};

/// Scores a session with the thresholds of its own case document (thresholds_from_case);
/// throws session::SessionError naming `source` if the case document is invalid.
Score score_session(const session::Session& session, const std::string& source);
/// Same with explicit thresholds.
Score score_session(const session::Session& session, const std::string& source, const Thresholds& thresholds);

/// The same score from a stream, in one pass over its samples, none of them kept: memory is
/// that of the case (grids, maps) and of the contact path (a point per 0.5 mm the contact
/// moved), not of the session's length (docs/scoring.md, "Memory"). Throws what
/// read_session and then score_session would, in the same order.
Score score_stream(session::SampleStream& stream, const std::string& source);
Score score_stream(session::SampleStream& stream, const std::string& source, const Thresholds& thresholds);

/// The full result as JSON; has at least passed, sensitivity, false_positives,
/// localization_error_mm, coverage, deep_coverage, duration_s, peak_force_n.
/// `with_maps` adds the per-cell maps (large).
nlohmann::json to_json(const Score& score, bool with_maps = false);

/// The score `to_json` wrote (with or without maps), read back; the thresholds are not in
/// the JSON's exact form, so the caller gives them (thresholds_from_case of the session's
/// case). Throws std::invalid_argument "stored score: ..." for JSON that is not one.
Score score_from_json(const nlohmann::json& json, const Thresholds& thresholds);

/// A short text score card for a terminal (one metric per line, gates with PASS/FAIL).
std::string summary_text(const Score& score);

}  // namespace palpa::score
