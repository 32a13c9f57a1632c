#pragma once
// The HTML page of one session: self-contained (images inline as data: URIs, inline CSS,
// no script, no external asset), every piece of text escaped.
#include <cstdint>
#include <string>
#include <vector>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"
#include "palpa/session/session.hpp"

namespace palpa::report {

class ForceTrace;

/// The three figures as PNG bytes.
struct SessionImages {
  std::vector<std::uint8_t> coverage, pressure, force;
};

/// Renders coverage_heatmap, pressure_map and force_plot as PNGs.
SessionImages render_images(const session::Session& session, const score::Score& score);
/// The same with the force plot from a trace gathered while the samples streamed by.
SessionImages render_images(const ForceTrace& trace, const score::Score& score);

/// The page: pass/fail banner with the gate messages, metrics table, the three figures,
/// tumours, marks, notes and the thresholds used.
std::string session_html(const SessionHeader& header, const score::Score& score, const SessionImages& images);

/// The page's shared style sheet (also used by the cohort page).
const std::string& report_css();

/// <img> with the PNG inline.
std::string png_img(const std::vector<std::uint8_t>& png, const std::string& alt);

}  // namespace palpa::report
