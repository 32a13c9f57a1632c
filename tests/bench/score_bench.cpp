// Scoring throughput: a synthetic 5-minute 1 kHz session (300,000 samples) on the default
// breast-like case, a strip search in contact with varying depth and force.
#include <benchmark/benchmark.h>

#include <cmath>

#include "../core/score/score_fixture.hpp"
#include "palpa/score/score.hpp"

namespace {

palpa::session::Session five_minute_session() {
  palpa::test::SessionBuilder b(palpa::test::case_document("default.json"));
  constexpr int kSamples = 300'000;
  constexpr int kStrips = 12;
  const int per_strip = kSamples / kStrips;
  for (int k = 0; k < kSamples; ++k) {
    const int strip = k / per_strip;
    const double a = (k % per_strip) / double(per_strip);
    const double u = 0.05 + 0.9 * (strip + 0.5) / kStrips;
    const double v = 0.05 + 0.9 * (strip % 2 == 0 ? a : 1.0 - a);
    const double depth = 0.004 + 0.003 * std::sin(k * 0.01);
    b.contact_uv(0, u, v, depth, 3.0 + 2.0 * std::sin(k * 0.003));
    if (k == kSamples / 2) b.event(palpa::session::EventKind::Mark, 1, {0.0245, 0.02, 0.03});
  }
  return b.finish();
}

void BM_ScoreFiveMinuteSession(benchmark::State& state) {
  const palpa::session::Session session = five_minute_session();
  for (auto _ : state) {
    palpa::score::Score s = palpa::score::score_session(session, "bench");
    benchmark::DoNotOptimize(s.score);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(session.samples.size()));
  state.SetLabel("items = samples");
}
BENCHMARK(BM_ScoreFiveMinuteSession)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
