// Replay logic of the review mode against hand-made sessions: the sample standing at t,
// the thinned contact path, the marks standing at t and the time span.
#include <gtest/gtest.h>

#include "palpa/session/replay.hpp"

namespace palpa::session {
namespace {

engine::Sample sample(double t, double x, std::int32_t body) {
  engine::Sample s;
  s.t = t;
  s.position = {x, 0.0, 0.0};
  s.body = body;
  return s;
}

// Ticks at 0, 0.001, ... 0.009 s.
std::vector<engine::Sample> ten_ticks() {
  std::vector<engine::Sample> samples;
  for (int i = 0; i < 10; ++i) samples.push_back(sample(0.001 * i, 0.001 * i, 0));
  return samples;
}

TEST(SessionReplay, SampleAtIsTheLastSampleAtOrBeforeT) {
  const auto samples = ten_ticks();
  EXPECT_EQ(sample_at(samples, 0.0), 0u);
  EXPECT_EQ(sample_at(samples, 0.0049), 4u);   // between ticks 4 and 5: tick 4 stands
  EXPECT_EQ(sample_at(samples, samples[5].t), 5u);  // exactly on a tick
  EXPECT_EQ(sample_at(samples, samples[9].t), 9u);
  EXPECT_EQ(sample_at(samples, 1.0), 9u);      // after the end: the last one
  EXPECT_EQ(sample_at(samples, -1.0), 0u);     // before the start: the first one
  EXPECT_EQ(sample_at({}, 0.5), 0u);
}

TEST(SessionReplay, SampleAtMatchesALinearScan) {
  // Uneven times (a paused stretch): binary search must agree with the obvious scan.
  std::vector<engine::Sample> samples;
  const double times[] = {0.0, 0.001, 0.002, 0.5, 0.501, 2.0, 2.001, 2.002};
  for (double t : times) samples.push_back(sample(t, t, 0));
  for (double t = -0.1; t < 2.1; t += 0.0137) {
    std::size_t expected = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (samples[i].t <= t) expected = i;
    }
    EXPECT_EQ(sample_at(samples, t), expected) << "t = " << t;
  }
}

TEST(SessionReplay, ContactPathSplitsAtLiftsAndKeepsStretchEnds) {
  // Contact on 0..4, off on 5..6, contact on 7..9; x advances 1 mm per tick.
  auto samples = ten_ticks();
  samples[5].body = -1;
  samples[6].body = -1;
  const auto path = contact_path(samples, 0.0025);  // keep points at least 2.5 mm apart
  ASSERT_EQ(path.size(), 2u);
  // First stretch: 0 (start), 3 (3 mm from 0), 4 (its end).
  ASSERT_EQ(path[0].size(), 3u);
  EXPECT_EQ(path[0][0].sample, 0u);
  EXPECT_EQ(path[0][1].sample, 3u);
  EXPECT_EQ(path[0][2].sample, 4u);
  EXPECT_DOUBLE_EQ(path[0][1].position[0], 0.003);
  // Second stretch: 7 (start), 9 (its end; only 2 mm from 7, kept as the end).
  ASSERT_EQ(path[1].size(), 2u);
  EXPECT_EQ(path[1][0].sample, 7u);
  EXPECT_EQ(path[1][1].sample, 9u);
}

TEST(SessionReplay, ContactPathWithoutThinningKeepsEveryContactSample) {
  auto samples = ten_ticks();
  samples[0].body = -1;
  const auto path = contact_path(samples, 0.0);
  ASSERT_EQ(path.size(), 1u);
  ASSERT_EQ(path[0].size(), 9u);
  for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(path[0][k].sample, k + 1);
  // A single contact sample is a path of one point.
  std::vector<engine::Sample> one{sample(0.0, 0.0, -1), sample(0.001, 0.0, 2), sample(0.002, 0.0, -1)};
  const auto single = contact_path(one, 0.001);
  ASSERT_EQ(single.size(), 1u);
  ASSERT_EQ(single[0].size(), 1u);
  EXPECT_EQ(single[0][0].sample, 1u);
  EXPECT_TRUE(contact_path({}, 0.001).empty());
}

Event event(double t, EventKind kind, std::int64_t mark = -1, double x = 0.0) {
  Event e;
  e.t = t;
  e.kind = kind;
  e.mark = mark;
  e.position = {x, 0.0, 0.0};
  return e;
}

TEST(SessionReplay, MarksAtFollowPlacementsAndRemovals) {
  const std::vector<Event> events{event(0.0, EventKind::Start), event(1.0, EventKind::Mark, 1, 0.01),
                                  event(2.0, EventKind::Mark, 2, 0.02), event(3.0, EventKind::Unmark, 1),
                                  event(4.0, EventKind::End)};
  EXPECT_TRUE(marks_at(events, 0.5).empty());
  ASSERT_EQ(marks_at(events, 1.0).size(), 1u);  // placed exactly at t: standing
  EXPECT_EQ(marks_at(events, 1.0)[0].id, 1);
  const auto at_2_5 = marks_at(events, 2.5);
  ASSERT_EQ(at_2_5.size(), 2u);
  EXPECT_EQ(at_2_5[0].id, 1);
  EXPECT_EQ(at_2_5[1].id, 2);
  EXPECT_DOUBLE_EQ(at_2_5[1].position[0], 0.02);
  EXPECT_DOUBLE_EQ(at_2_5[1].t, 2.0);
  const auto at_end = marks_at(events, 10.0);
  ASSERT_EQ(at_end.size(), 1u);
  EXPECT_EQ(at_end[0].id, 2);
}

TEST(SessionReplay, TimeSpanRunsFromTheFirstSampleToTheEnd) {
  Session session;
  session.samples = ten_ticks();
  EXPECT_DOUBLE_EQ(time_span(session).start, 0.0);
  EXPECT_DOUBLE_EQ(time_span(session).end, 0.009);
  session.events = {event(0.0, EventKind::Start), event(0.02, EventKind::End)};
  EXPECT_DOUBLE_EQ(time_span(session).end, 0.02);  // the End event after the last tick
}

}  // namespace
}  // namespace palpa::session
