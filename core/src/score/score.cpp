#include "palpa/score/score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "contour_grid.hpp"
#include "coverage.hpp"
#include "marks.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/scene/scene.hpp"
#include "search_pattern.hpp"

namespace palpa::score {
namespace {

using detail::Vec3;

constexpr double kStampMove = 0.0005;  // m the contact moves before the pad is stamped again
constexpr double kCellSize = 0.002;    // m: coverage cells on the top contour

// A share in whole percent, rounded down: 79.6 % of an area is not the 80 % a gate needs,
// and must not read as if it were (the 1e-9 keeps 0.95, 94.99999... in binary, at 95).
double percent_down(double share) { return std::floor(100.0 * share + 1e-9); }

std::string printf_text(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// The active part of a session: start to end minus pauses (docs/scoring.md, "Duration").
struct Timeline {
  double start = 0.0, end = 0.0;
  std::vector<std::pair<double, double>> pauses;  // clipped to [start, end], in order
  double active = 0.0;
};

Timeline timeline_of(const session::Session& s) {
  Timeline tl;
  std::vector<session::Event> events = s.events;
  std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
  bool have_start = false, have_end = false;
  for (const auto& e : events) {
    if (e.kind == session::EventKind::Start && !have_start) {
      tl.start = e.t;
      have_start = true;
    }
    if (e.kind == session::EventKind::End && !have_end) {
      tl.end = e.t;
      have_end = true;
    }
  }
  if (!have_start) tl.start = s.samples.empty() ? 0.0 : s.samples.front().t;
  if (!have_end) tl.end = s.samples.empty() ? tl.start : s.samples.back().t;
  tl.end = std::max(tl.end, tl.start);

  bool paused = false;
  double since = 0.0;
  auto add = [&](double a, double b) {
    a = std::max(a, tl.start);
    b = std::min(b, tl.end);
    if (b > a) tl.pauses.emplace_back(a, b);
  };
  for (const auto& e : events) {
    if (e.kind == session::EventKind::Pause && !paused) {
      paused = true;
      since = e.t;
    } else if (e.kind == session::EventKind::Resume && paused) {
      paused = false;
      add(since, e.t);
    }
  }
  if (paused) add(since, tl.end);
  tl.active = tl.end - tl.start;
  for (const auto& [a, b] : tl.pauses) tl.active -= b - a;
  tl.active = std::max(0.0, tl.active);
  return tl;
}

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

std::string reason_of(const io::CaseError& e) {
  if (e.problems().empty()) return e.what();
  return e.problems().front().where + ": " + e.problems().front().reason;
}

std::string tumour_text(const TumourResult& t, double depth_m) {
  std::string s = printf_text("the %.0f mm mass %.0f mm deep at ", 2000.0 * t.radius, 1000.0 * depth_m);
  s += printf_text("(%.0f, %.0f, %.0f) mm in ", 1000.0 * t.center[0], 1000.0 * t.center[1], 1000.0 * t.center[2]);
  s += t.body;
  return s;
}

}  // namespace

Score score_session(const session::Session& session, const std::string& source) {
  std::vector<io::Problem> problems;
  const Thresholds thresholds = thresholds_from_case(session.info.case_document, problems);
  if (!problems.empty()) {
    throw session::SessionError(source, "meta case", problems.front().where + ": " + problems.front().reason);
  }
  return score_session(session, source, thresholds);
}

Score score_session(const session::Session& session, const std::string& source, const Thresholds& thresholds) {
  const Thresholds& th = thresholds;
  // The case as palpated, with its ground truth.
  io::CaseFile file;
  try {
    file = io::parse_case(session.info.case_document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                          source);
  } catch (const io::CaseError& e) {
    throw session::SessionError(source, "meta case", reason_of(e));
  }
  std::optional<scene::Scene> built;
  try {
    built.emplace(scene::Scene::build(file, source));
  } catch (const io::CaseError& e) {
    throw session::SessionError(source, "meta case", reason_of(e));
  } catch (const std::exception& e) {
    throw session::SessionError(source, "meta case", e.what());
  }
  const scene::Scene& scene = *built;
  const int body_count = static_cast<int>(scene.size());

  Score out;
  out.thresholds = th;
  out.complete = session.complete;
  out.abandoned = session::is_abandoned(session);
  out.samples = session.samples.size();

  // Coverage grids, one per body, restricted to the exam region.
  std::vector<detail::ContourGrid> grids;
  grids.reserve(scene.size());
  for (std::size_t b = 0; b < scene.size(); ++b) {
    std::vector<RegionPart> parts;
    for (const auto& p : th.exam_region)
      if (p.body == scene.body(b).body.id()) parts.push_back(p);
    grids.emplace_back(scene.body(b).body, parts, th.exam_region.empty(), kCellSize);
  }
  for (const auto& p : th.exam_region) {
    bool known = false;
    for (std::size_t b = 0; b < scene.size(); ++b) known = known || p.body == scene.body(b).body.id();
    if (!known) out.notes.push_back("exam region names an unknown body \"" + p.body + "\": ignored");
  }
  std::vector<detail::Coverage> coverage;
  std::vector<const detail::ContourGrid*> grid_ptrs;
  for (const auto& g : grids) {
    coverage.emplace_back(g);
    grid_ptrs.push_back(&g);
  }

  // Marks and tumours on the top contour.
  scene::ProbeState state = scene.make_state();
  std::vector<detail::Landing> mark_tops, tumour_tops;
  for (const auto& m : detail::standing(session.events)) {
    MarkResult r;
    r.id = m.id;
    r.t = m.t;
    r.position = m.position;
    out.marks.push_back(r);
    mark_tops.push_back(detail::land_on_scene(scene, Vec3(m.position[0], m.position[1], m.position[2]), state));
  }
  std::vector<double> tumour_depth;
  for (const auto& t : file.tumours) {
    TumourResult r;
    r.body = t.body;
    r.center = t.center;
    r.radius = t.radius;
    r.detectable = 2.0 * t.radius >= th.detectable_diameter;
    int index = 0;
    for (int b = 0; b < body_count; ++b)
      if (scene.body(static_cast<std::size_t>(b)).body.id() == t.body) index = b;
    const Vec3 c(t.center[0], t.center[1], t.center[2]);
    tumour_tops.push_back(detail::land_on_body(scene.body(static_cast<std::size_t>(index)), index, c));
    tumour_depth.push_back((tumour_tops.back().top - c).norm());
    out.tumours.push_back(r);
  }
  out.false_positives = detail::match_marks(mark_tops, tumour_tops, out.marks, out.tumours, th.hit_margin);
  int detectable = 0, found_detectable = 0;
  for (const auto& t : out.tumours) {
    if (t.found) out.localization_error_mm.push_back(t.localization_error_mm);
    if (!t.detectable) continue;
    ++detectable;
    if (t.found) ++found_detectable;
  }
  out.sensitivity = detectable == 0 ? 1.0 : double(found_detectable) / detectable;

  // One pass over the samples: active time, contact, pressure, coverage, force, path.
  const Timeline tl = timeline_of(session);
  out.duration_s = tl.active;
  const double rate = session.info.rate_hz > 0 ? session.info.rate_hz : 1000.0;
  const double dt_cap = 2.0 / rate;  // a gap in the recording does not count as contact
  const double palpate2 = th.palpate_radius * th.palpate_radius;

  std::vector<detail::PathPoint> path;
  std::vector<int> stamped;
  std::size_t pause_index = 0;
  bool was_contact = false, have_stamp = false;
  int stamp_body = -1, piece = 0;
  std::uint32_t stamp_number = 0;
  std::uint8_t stamp_level = 0;
  Vec3 stamp_top = Vec3::Zero();
  double pending_dwell = 0.0, pending_peak = 0.0;
  int cache_body = -1;
  double cache_u = std::numeric_limits<double>::quiet_NaN(), cache_v = cache_u, cache_radius = 0.0;
  Vec3 cache_top = Vec3::Zero();
  double near_sum = 0.0, search_sum = 0.0;
  std::size_t near_count = 0, search_count = 0, ignored = 0;

  auto flush = [&] {
    if (have_stamp && pending_dwell > 0.0)
      coverage[static_cast<std::size_t>(stamp_body)].add_dwell(stamped, pending_dwell, pending_peak);
    pending_dwell = pending_peak = 0.0;
  };

  const auto& samples = session.samples;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const engine::Sample& s = samples[k];
    const double force = std::sqrt(s.force[0] * s.force[0] + s.force[1] * s.force[1] + s.force[2] * s.force[2]);
    out.peak_force_n = std::max(out.peak_force_n, force);  // every sample: safety is about what was applied

    while (pause_index < tl.pauses.size() && tl.pauses[pause_index].second <= s.t) ++pause_index;
    const bool paused = pause_index < tl.pauses.size() && tl.pauses[pause_index].first <= s.t;
    const bool active = s.t >= tl.start && s.t <= tl.end && !paused && !s.fault;
    if (active && s.body >= body_count) ++ignored;
    // Non-finite parameters cannot be placed on the grid: such a sample is not contact.
    const bool contact = active && s.body >= 0 && s.body < body_count && std::isfinite(s.u) && std::isfinite(s.v);
    if (!contact) {
      if (was_contact) {
        flush();
        ++stamp_number;  // lifting off ends every cell's visit
        ++piece;
      }
      was_contact = false;
      continue;
    }
    const double dt =
        std::clamp(k + 1 < samples.size() ? samples[k + 1].t - s.t : 1.0 / rate, 0.0, dt_cap);
    const auto b = static_cast<std::size_t>(s.body);
    if (s.body != cache_body || s.u != cache_u || s.v != cache_v) {
      grids[b].lookup(s.u, s.v, cache_top, cache_radius);
      cache_body = s.body;
      cache_u = s.u;
      cache_v = s.v;
    }
    const Vec3& top = cache_top;
    const double depth = std::max(0.0, s.depth);
    const double ratio = cache_radius > 0.0 ? depth / (2.0 * cache_radius)
                                            : (depth > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    const std::uint8_t level = ratio < th.light_max ? 1 : ratio >= th.deep_min ? 3 : 2;
    (level == 1 ? out.pressure.light_s : level == 2 ? out.pressure.medium_s : out.pressure.deep_s) += dt;
    out.contact_time_s += dt;

    bool near = false;
    for (const auto& m : mark_tops) near = near || (m.body >= 0 && (m.top - top).squaredNorm() <= palpate2);
    (near ? near_sum : search_sum) += force;
    ++(near ? near_count : search_count);

    const bool new_piece = was_contact && have_stamp && s.body != stamp_body;
    if (new_piece) ++piece;
    if (!have_stamp || !was_contact || new_piece || level != stamp_level ||
        (top - stamp_top).squaredNorm() > kStampMove * kStampMove) {
      flush();
      if (new_piece) ++stamp_number;
      ++stamp_number;
      const int cell = grids[b].cell_of(s.u, s.v);
      coverage[b].stamp(top, cell, level, th.pad_radius, stamp_number, stamped);
      have_stamp = true;
      stamp_body = s.body;
      stamp_top = top;
      stamp_level = level;
      path.push_back({s.body, piece, s.u, s.v, top, coverage[b].visits(cell) >= 2});
    }
    pending_dwell += dt;
    pending_peak = std::max(pending_peak, force);
    was_contact = true;
  }
  flush();

  // Coverage of the exam region, and how compact the covered area is.
  double region = 0.0, covered = 0.0, deep = 0.0;
  Vec3 moment = Vec3::Zero();
  for (std::size_t b = 0; b < grids.size(); ++b) {
    const auto& area = grids[b].areas();
    const auto& level = coverage[b].level();
    region += grids[b].region_area();
    for (std::size_t c = 0; c < area.size(); ++c) {
      if (level[c] == 0) continue;
      covered += area[c];
      moment += area[c] * grids[b].centers()[c];
      if (level[c] == 3) deep += area[c];
    }
  }
  out.coverage = region > 0.0 ? clamp01(covered / region) : 0.0;
  out.deep_coverage = region > 0.0 ? clamp01(deep / region) : 0.0;
  bool compact = false;
  if (covered > 0.0) {
    // Radius of gyration r_g: a disc of area A has 2 pi r_g^2 = A. The covered area is one
    // compact patch when it fills at least half the disc its spread implies (not a
    // scatter or a ring) and that disc is at most half the exam region (one part of it).
    const Vec3 centroid = moment / covered;
    double spread = 0.0;
    for (std::size_t b = 0; b < grids.size(); ++b) {
      const auto& area = grids[b].areas();
      const auto& level = coverage[b].level();
      for (std::size_t c = 0; c < area.size(); ++c)
        if (level[c] != 0) spread += area[c] * (grids[b].centers()[c] - centroid).squaredNorm();
    }
    const double rg2 = spread / covered;
    const double disc = 2.0 * std::numbers::pi * rg2;
    compact = covered >= 0.5 * disc && disc <= 0.5 * region;
  }

  // Search pattern.
  out.pattern = detail::measure_pattern(path, grid_ptrs, th.pad_radius);
  out.pattern.efficiency =
      out.pattern.path_length_m > 0.0 ? clamp01(covered / (out.pattern.path_length_m * 2.0 * th.pad_radius)) : 0.0;
  out.pattern.kind = detail::classify_pattern(out.pattern, out.contact_time_s > 0.0, out.coverage, compact, th);

  out.palpate_search_ratio =
      near_count > 0 && search_count > 0 && search_sum > 0.0
          ? (near_sum / double(near_count)) / (search_sum / double(search_count))
          : 0.0;
  out.safe = out.peak_force_n <= th.max_force;
  out.short_exam = out.duration_s < th.min_duration;

  // Gates.
  {
    Gate g{"sensitivity", found_detectable == detectable, out.sensitivity, 1.0, ""};
    g.message = "Found " + std::to_string(found_detectable) + " of " + std::to_string(detectable) + " tumours";
    std::string missed;
    for (std::size_t k = 0; k < out.tumours.size(); ++k) {
      if (out.tumours[k].found || !out.tumours[k].detectable) continue;
      missed += missed.empty() ? ": " : "; ";
      missed += tumour_text(out.tumours[k], tumour_depth[k]);
    }
    g.message += missed.empty() ? "." : missed + (detectable - found_detectable == 1 ? " was missed." : " were missed.");
    out.gates.push_back(g);
  }
  {
    Gate g{"false_positives", out.false_positives <= th.max_false_positives, double(out.false_positives),
           double(th.max_false_positives), ""};
    g.message = std::to_string(out.false_positives) + (out.false_positives == 1 ? " mark" : " marks") +
                " matched no tumour (at most " + std::to_string(th.max_false_positives) + " allowed).";
    out.gates.push_back(g);
  }
  out.gates.push_back({"coverage", out.coverage >= th.min_coverage, out.coverage, th.min_coverage,
                       printf_text("Covered %.0f%% of the exam region (%.0f%% needed).", percent_down(out.coverage),
                                   100.0 * th.min_coverage)});
  out.gates.push_back({"deep_coverage", out.deep_coverage >= th.min_deep_coverage, out.deep_coverage,
                       th.min_deep_coverage,
                       printf_text("Pressed deep over %.0f%% of the exam region (%.0f%% needed).",
                                   percent_down(out.deep_coverage), 100.0 * th.min_deep_coverage)});
  out.gates.push_back({"safety", out.safe, out.peak_force_n, th.max_force,
                       printf_text(out.safe ? "Peak force %.1f N (limit %.1f N)." : "Peak force %.1f N is above the %.1f N limit.",
                                   out.peak_force_n, th.max_force)});
  out.passed = std::all_of(out.gates.begin(), out.gates.end(), [](const Gate& g) { return g.passed; });

  // Sub-scores.
  const double fp_zero = 2.0 * th.max_false_positives + 2.0;
  double localization = out.tumours.empty() ? 1.0 : 0.0;
  if (!out.localization_error_mm.empty()) {
    double sum = 0.0;
    for (const auto& t : out.tumours)
      if (t.found) sum += clamp01(1.0 - t.localization_error_mm / (1000.0 * (t.radius + th.hit_margin)));
    localization = sum / double(out.localization_error_mm.size());
  }
  double pressure = 0.0;
  if (out.contact_time_s > 0.0) {
    for (double level_s : {out.pressure.light_s, out.pressure.medium_s, out.pressure.deep_s})
      pressure += clamp01(level_s / out.contact_time_s / 0.10) / 3.0;
  }
  const std::string& kind = out.pattern.kind;
  const double pattern = kind == "efficient" ? 1.0 : kind == "thorough" ? 0.75 : kind == "none" ? 0.0 : 0.25;
  out.subscores = {
      {"sensitivity", out.sensitivity, th.weight_sensitivity},
      {"false_positives", clamp01(1.0 - out.false_positives / fp_zero), th.weight_false_positives},
      {"localization", localization, th.weight_localization},
      {"coverage", clamp01((out.coverage - 0.5) / (th.expert_coverage - 0.5)), th.weight_coverage},
      {"deep_coverage", th.min_deep_coverage > 0.0 ? clamp01(out.deep_coverage / th.min_deep_coverage) : 1.0,
       th.weight_deep_coverage},
      {"pattern", pattern, th.weight_pattern},
      {"pressure", pressure, th.weight_pressure},
  };
  double weight_sum = 0.0;
  for (const auto& s : out.subscores) weight_sum += s.weight;
  for (auto& s : out.subscores) {
    s.weight = weight_sum > 0.0 ? s.weight / weight_sum : 0.0;
    out.score += s.weight * s.value;
  }

  // Notes for the trainee and the instructor.
  if (out.abandoned) {
    out.passed = false;
    out.notes.push_back("abandoned by the trainee: not an exam, left out of learning curves");
  }
  if (!session.complete) {
    out.notes.push_back(printf_text("session incomplete (no end event): scored up to t = %.1f s",
                                    samples.empty() ? tl.end : samples.back().t));
  }
  if (samples.empty()) out.notes.push_back("no samples recorded");
  if (out.short_exam) {
    out.notes.push_back(printf_text("short exam: %.0f s of active time (at least %.0f s expected)", out.duration_s,
                                    th.min_duration));
  }
  for (std::size_t k = 0; k < out.tumours.size(); ++k) {
    if (out.tumours[k].detectable) continue;
    out.notes.push_back(printf_text("tumour %.0f (%.1f mm across) is smaller than the detectable size (%.1f mm): it does "
                                    "not count for the sensitivity gate",
                                    double(k + 1), 2000.0 * out.tumours[k].radius, 1000.0 * th.detectable_diameter));
  }
  for (const auto& m : out.marks) {
    if (m.duplicate) out.notes.push_back("mark " + std::to_string(m.id) + " marks a tumour already found (duplicate)");
  }
  if (out.palpate_search_ratio > 0.0 &&
      (out.palpate_search_ratio < th.palpate_ratio_low || out.palpate_search_ratio > th.palpate_ratio_high)) {
    out.notes.push_back(printf_text("palpate/search force ratio %.2f is outside the expert band %.2f-%.2f",
                                    out.palpate_search_ratio, th.palpate_ratio_low, th.palpate_ratio_high));
  }
  if (out.pattern.strip_spacing_mm > 1250.0 * th.strip_spacing) {
    out.notes.push_back(printf_text("strips %.0f mm apart: wider than one finger pad (%.0f mm)",
                                    out.pattern.strip_spacing_mm, 1000.0 * th.strip_spacing));
  }
  if (ignored > 0) {
    out.notes.push_back(printf_text("%.0f samples name a body the case does not have: ignored", double(ignored)));
  }

  // Maps for reports.
  for (std::size_t b = 0; b < grids.size(); ++b) {
    BodyMap map;
    map.body = scene.body(b).body.id();
    map.rows = grids[b].rows();
    map.cols = grids[b].cols();
    map.area = grids[b].areas();
    map.center.reserve(grids[b].centers().size());
    for (const auto& c : grids[b].centers())
      map.center.push_back({static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())});
    map.level = coverage[b].level();
    map.dwell_s = coverage[b].dwell();
    map.peak_force_n = coverage[b].peak_force();
    out.maps.push_back(std::move(map));
  }
  return out;
}

}  // namespace palpa::score
