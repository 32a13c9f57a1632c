#pragma once
// A small synthetic scored session for the report tests: one flat body seen from above as
// a 4 x 4 grid of 20 mm cells centred at x, y in {-30, -10, 10, 30} mm (cell (i, j) at
// x = -30 + 20 i, y = -30 + 20 j), cell (3, 3) outside the exam region; one tumour found by
// mark 1 and one missed; mark 2 a false positive.
#include <string>

#include "palpa/report/session_header.hpp"
#include "palpa/score/score.hpp"

namespace palpa::report::testing {

inline double cell_x(int i) { return -0.03 + 0.02 * i; }
inline double cell_y(int j) { return -0.03 + 0.02 * j; }

inline score::Score synthetic_score() {
  score::Score s;
  s.passed = false;
  s.score = 0.6125;
  s.sensitivity = 0.5;
  s.false_positives = 1;
  s.localization_error_mm = {2.5, 3.5};
  s.coverage = 0.4;
  s.deep_coverage = 0.1;
  s.duration_s = 183.25;
  s.contact_time_s = 120.5;
  s.peak_force_n = 7.25;
  s.pattern.kind = score::PatternKind::Sporadic;
  s.pressure = {40.0, 50.0, 30.5};
  s.samples = 183250;
  s.gates = {{"sensitivity", false, 0.5, 1.0, "You found 1 of 2 tumours."},
             {"coverage", false, 0.4, 0.9, "You covered 40 % of the region; 90 % is needed."}};
  score::BodyMap m;
  m.body = "flat";
  m.rows = 4;
  m.cols = 4;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      m.area.push_back(i == 3 && j == 3 ? 0.0 : 4e-4);
      m.center.push_back({static_cast<float>(cell_x(i)), static_cast<float>(cell_y(j)), 0.02F});
      m.level.push_back(0);
      m.dwell_s.push_back(0.0F);
      m.peak_force_n.push_back(0.0F);
    }
  m.dwell_s[1 * 4 + 2] = 2.0F;  // the most dwelt-on cell: (1, 2) at (-10, 10) mm
  m.level[1 * 4 + 2] = 3;
  m.dwell_s[0] = 0.5F;
  m.level[0] = 1;
  s.maps.push_back(m);
  score::TumourResult found;
  found.body = "flat";
  found.center = {0.01, 0.01, 0.0};
  found.radius = 0.005;
  found.found = true;
  found.mark = 1;
  found.localization_error_mm = 2.5;
  score::TumourResult missed;
  missed.body = "flat";
  missed.center = {-0.025, 0.025, 0.0};
  missed.radius = 0.004;
  s.tumours = {found, missed};
  s.marks = {{1, 30.0, {0.012, 0.011, 0.02}, 0, false, 2.5}, {2, 90.0, {0.03, -0.03, 0.02}, -1, false, 35.0}};
  s.notes = {"a note with <b>markup</b> & ampersand"};
  return s;
}

inline SessionHeader synthetic_header() {
  SessionHeader h;
  h.id = "3f2a9c";
  h.trainee = "alice";
  h.case_title = "Flat 5x5: plane skeleton, polynomial radius";
  h.case_source = "data/cases/flat-5x5.json";
  h.device = "virtual";
  h.software_version = "0.1.0";
  h.started_at = "2026-11-22T16:40:00Z";
  h.file = "sessions/alice-1.palpa";
  return h;
}

}  // namespace palpa::report::testing
