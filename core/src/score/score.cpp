#include "palpa/score/score.hpp"
#include "palpa/score/figures.hpp"

#include <algorithm>
#include <functional>
#include <optional>

#include "../common/numeric.hpp"
#include "exam_grids.hpp"
#include "marks.hpp"
#include "palpa/mat/mat_body.hpp"
#include "palpa/scene/scene.hpp"
#include "sample_pass.hpp"
#include "search_pattern.hpp"
#include "timeline.hpp"
#include "verdict.hpp"
#include "palpa/vec3.hpp"

// score_session in stages (docs/scoring.md): the case as palpated, marks against tumours,
// one pass over the samples, the covered area and the search pattern, then the verdict.
namespace palpa::score {
namespace {

using detail::Timeline;

std::string reason_of(const io::CaseError& e) {
  if (e.problems().empty()) return e.what();
  return e.problems().front().where + ": " + e.problems().front().reason;
}

// The case as palpated, with its ground truth, from the session's copy of it.
struct PalpatedCase {
  io::CaseFile file;
  std::optional<scene::Scene> scene;
};

PalpatedCase palpated_case(const session::Session& session, const std::string& source) {
  PalpatedCase out;
  try {
    out.file = io::parse_case(
        session.info.case_document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), source);
    out.scene.emplace(scene::Scene::build(out.file, source));
  } catch (const io::CaseError& e) {
    throw session::SessionError(source, "meta case", reason_of(e));
  } catch (const std::exception& e) {
    throw session::SessionError(source, "meta case", e.what());
  }
  return out;
}

// Where the marks and tumours land on the top contour; each tumour's depth below it.
struct TopPoints {
  std::vector<detail::Landing> marks, tumours;
  std::vector<double> tumour_depth;
};

TopPoints mark_results(const session::Session& session, const scene::Scene& scene, Score& out) {
  TopPoints tops;
  scene::ProbeState state = scene.make_state();
  for (const auto& m : detail::standing(session.events)) {
    out.marks.push_back({m.id, m.t, m.position});
    tops.marks.push_back(detail::land_on_scene(scene, to_vec3(m.position), state));
  }
  return tops;
}

void tumour_results(const io::CaseFile& file, const scene::Scene& scene, const Thresholds& th, TopPoints& tops,
                    Score& out) {
  for (const auto& t : file.tumours) {
    TumourResult r;
    r.body = t.body;
    r.center = t.center;
    r.radius = t.radius;
    r.detectable = 2.0 * t.radius >= th.detectable_diameter;
    int index = 0;
    for (std::size_t b = 0; b < scene.size(); ++b)
      if (scene.body(b).body.id() == t.body) index = static_cast<int>(b);
    const Vec3 c(t.center[0], t.center[1], t.center[2]);
    tops.tumours.push_back(detail::land_on_body(scene.body(static_cast<std::size_t>(index)), index, c));
    tops.tumour_depth.push_back((tops.tumours.back().top - c).norm());
    out.tumours.push_back(r);
  }
}

void match_and_count(const TopPoints& tops, const Thresholds& th, Score& out) {
  out.false_positives = detail::match_marks(tops.marks, tops.tumours, out.marks, out.tumours, th.hit_margin);
  int detectable = 0, found_detectable = 0;
  for (const auto& t : out.tumours) {
    if (t.found) out.localization_error_mm.push_back(t.localization_error_mm);
    if (!t.detectable) continue;
    ++detectable;
    if (t.found) ++found_detectable;
  }
  out.sensitivity = detectable == 0 ? 1.0 : double(found_detectable) / detectable;
}

void take_pass(const detail::SamplePass& pass, const Timeline& tl, Score& out) {
  out.duration_s = tl.active;
  out.peak_force_n = pass.peak_force_n;
  out.contact_time_s = pass.contact_time_s;
  out.pressure = pass.pressure;
  out.palpate_search_ratio = pass.palpate_search_ratio();
}

void measure_area_and_pattern(const detail::ExamGrids& exam, const detail::SamplePass& pass, const Thresholds& th,
                              Score& out) {
  const detail::CoveredArea area = detail::covered_area(exam);
  out.coverage = area.region > 0.0 ? clamp01(area.covered / area.region) : 0.0;
  out.deep_coverage = area.region > 0.0 ? clamp01(area.deep / area.region) : 0.0;
  out.pattern = detail::measure_pattern(pass.path, exam.grid_ptrs, th.pad_radius);
  const double swept = out.pattern.path_length_m * 2.0 * th.pad_radius;  // path x pad diameter
  out.pattern.efficiency = out.pattern.path_length_m > 0.0 ? clamp01(area.covered / swept) : 0.0;
  out.pattern.kind = detail::classify_pattern(out.pattern, out.contact_time_s > 0.0, out.coverage, area.compact, th);
}

void judge(const session::Session& session, const Timeline& tl, const TopPoints& tops, const detail::SamplePass& pass,
           const Thresholds& th, Score& out) {
  out.safe = shown_force_n(out.peak_force_n) <= th.max_force + 1e-9;  // the figure shown (figures.hpp)
  out.short_exam = out.duration_s < th.min_duration;
  out.gates = detail::gates_of(out, tops.tumour_depth, th);
  out.passed = std::all_of(out.gates.begin(), out.gates.end(), [](const Gate& g) { return g.passed; });
  out.subscores = detail::subscores_of(out, th);
  for (const auto& s : out.subscores) out.score += s.weight * s.value;
  if (out.abandoned) out.passed = false;  // not an exam
  detail::add_notes(out, session.complete, pass.last_t, tl, pass.ignored, th);
}

Thresholds thresholds_of(const session::Session& session, const std::string& source) {
  std::vector<io::Problem> problems;
  const Thresholds thresholds = thresholds_from_case(session.info.case_document, problems);
  if (!problems.empty()) {
    throw session::SessionError(source, "meta case", problems.front().where + ": " + problems.front().reason);
  }
  return thresholds;
}

// Hands the samples to the pass, in order, in as many pieces as it likes.
using Feed = std::function<void(detail::SamplePass&)>;

// Everything after the case: `session` without its samples (info, events), which `feed`
// gives; `times` are their first and last time (nothing: no samples).
Score score_samples(const session::Session& session, const PalpatedCase& palpated, const Thresholds& th,
                    const std::optional<session::SampleTimes>& times, const Feed& feed) {
  const scene::Scene& scene = *palpated.scene;
  Score out;
  out.thresholds = th;
  out.complete = session.complete;
  out.abandoned = session::is_abandoned(session);

  detail::ExamGrids exam(scene, th, out.notes);
  TopPoints tops = mark_results(session, scene, out);
  tumour_results(palpated.file, scene, th, tops, out);
  match_and_count(tops, th, out);

  const Timeline tl = detail::timeline_of(session.events, times);
  detail::SamplePass pass(exam, tops.marks, tl, th, session.info.rate_hz);
  feed(pass);
  pass.finish();
  out.samples = pass.sample_count;
  take_pass(pass, tl, out);
  measure_area_and_pattern(exam, pass, th, out);
  judge(session, tl, tops, pass, th, out);
  out.maps = detail::coverage_maps(scene, exam);
  return out;
}

std::optional<session::SampleTimes> times_of(const std::vector<engine::Sample>& samples) {
  if (samples.empty()) return std::nullopt;
  return session::SampleTimes{samples.front().t, samples.back().t};
}

// A case the reader accepted but scoring cannot use is reported after the samples were
// read and checked, as when they were all read first: a file with a bad sample as well
// gets the sample's message, whichever way it is scored.
template <class Make>
auto after_the_samples(session::SampleStream& stream, Make&& make) {
  try {
    return make();
  } catch (const session::SessionError&) {
    while (!stream.next().empty()) {
    }
    throw;
  }
}

}  // namespace

Score score_session(const session::Session& session, const std::string& source) {
  return score_session(session, source, thresholds_of(session, source));
}

Score score_session(const session::Session& session, const std::string& source, const Thresholds& th) {
  const PalpatedCase palpated = palpated_case(session, source);
  return score_samples(session, palpated, th, times_of(session.samples),
                       [&](detail::SamplePass& pass) { pass.add(session.samples); });
}

Score score_stream(session::SampleStream& stream, const std::string& source) {
  const Thresholds th = after_the_samples(stream, [&] { return thresholds_of(stream.head(), source); });
  return score_stream(stream, source, th);
}

Score score_stream(session::SampleStream& stream, const std::string& source, const Thresholds& th) {
  const PalpatedCase palpated = after_the_samples(stream, [&] { return palpated_case(stream.head(), source); });
  return score_samples(stream.head(), palpated, th, stream.sample_times(), [&](detail::SamplePass& pass) {
    for (auto block = stream.next(); !block.empty(); block = stream.next()) pass.add(block);
  });
}

}  // namespace palpa::score
