// Session file throughput: samples appended per second (with a commit every 250 samples,
// as the recorder does at 1 kHz), the finish (format 2: compacting the rows into blocks),
// samples read per second, and bytes per sample, for format 1 (rows) and 2 (blocks).
//   cmake --build build/release --target session_bench && build/release/tests/session_bench
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "palpa/io/case_file.hpp"
#include "palpa/session/session_reader.hpp"
#include "palpa/session/session_writer.hpp"

namespace {

using namespace palpa;

std::filesystem::path scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "palpa-session-bench-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    return std::filesystem::path(pattern);
  }();
  return dir;
}

session::SessionInfo info() {
  session::SessionInfo i;
  i.trainee = "bench";
  i.device = "virtual";
  i.case_source = "default.json";
  i.case_document = io::to_json(io::load_case(PALPA_SOURCE_DIR "/data/cases/default.json"));
  return i;
}

// A plausible palpation trace: two thirds of the ticks in contact, smooth motion.
engine::Sample sample_at(std::int64_t k) {
  const double x = static_cast<double>(k);
  engine::Sample s;
  s.t = x / 1000.0;
  s.position = {0.02 * std::sin(x / 970.0), 0.01 * std::cos(x / 890.0), 0.03 - 0.005 * std::sin(x / 300.0)};
  if (k % 3 != 0) {
    s.force = {0.1 * std::sin(x / 70.0), 0.1 * std::cos(x / 110.0), 2.0 + std::sin(x / 300.0)};
    s.body = 0;
    s.u = 0.5 + 0.4 * std::sin(x / 970.0);
    s.v = 0.5 + 0.4 * std::cos(x / 890.0);
    s.depth = 0.005 * (1.0 + std::sin(x / 300.0));
  }
  return s;
}

// Commits every `commit_every` samples (the recorder: 250 at 1 kHz) and once at the end.
// The trace, computed once so that the timing is the writer's alone.
const std::vector<engine::Sample>& trace(std::int64_t n) {
  static std::vector<engine::Sample> samples;
  while (static_cast<std::int64_t>(samples.size()) < n) samples.push_back(sample_at(static_cast<std::int64_t>(samples.size())));
  return samples;
}

std::filesystem::path write_file(const std::string& name, std::int64_t n, std::int64_t commit_every, int format,
                                 benchmark::State* state) {
  const auto path = scratch_dir() / name;
  std::filesystem::remove(path);
  const auto& samples = trace(n);
  session::SessionWriter writer(path, info(), session::WriterOptions{format});
  if (state != nullptr) state->ResumeTiming();
  for (std::int64_t k = 0; k < n; ++k) {
    writer.append(samples[static_cast<std::size_t>(k)]);
    if (k % commit_every == commit_every - 1) writer.commit();
  }
  writer.commit();
  if (state != nullptr) state->PauseTiming();
  writer.finish();
  return path;
}

void BM_SessionAppend(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  std::uintmax_t bytes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const auto path = write_file("append.palpa", n, state.range(1), static_cast<int>(state.range(2)), &state);
    bytes = std::filesystem::file_size(path);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["bytes_per_sample"] = static_cast<double>(bytes) / static_cast<double>(n);
  state.counters["MB_per_minute_at_1kHz"] = static_cast<double>(bytes) / static_cast<double>(n) * 60000.0 / 1e6;
}
// 60000 samples: a minute at 1 kHz; committing every 250 samples, or only at the end; the
// third argument is the format finish() leaves (the size counters are that file's). Five
// minutes (300000) for the size of a whole exam.
BENCHMARK(BM_SessionAppend)
    ->Args({60000, 250, 1})
    ->Args({60000, 60000, 1})
    ->Args({60000, 250, 2})
    ->Args({300000, 250, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// finish() alone: format 1 checkpoints and leaves WAL mode; format 2 also compacts the rows
// into blocks and vacuums.
void BM_SessionFinish(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const auto& samples = trace(n);
  for (auto _ : state) {
    state.PauseTiming();
    const auto path = scratch_dir() / "finish.palpa";
    std::filesystem::remove(path);
    session::SessionWriter writer(path, info(), session::WriterOptions{static_cast<int>(state.range(1))});
    for (std::int64_t k = 0; k < n; ++k) {
      writer.append(samples[static_cast<std::size_t>(k)]);
      if (k % 250 == 249) writer.commit();
    }
    writer.commit();
    state.ResumeTiming();
    writer.finish();
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_SessionFinish)->Args({60000, 1})->Args({60000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SessionRead(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const auto path = write_file("read.palpa", n, 250, static_cast<int>(state.range(1)), nullptr);
  for (auto _ : state) {
    const auto s = session::read_session(path);
    if (static_cast<std::int64_t>(s.samples.size()) != n) state.SkipWithError("wrong sample count");
    benchmark::DoNotOptimize(s.samples.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_SessionRead)->Args({60000, 1})->Args({60000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir(), ec);
  return 0;
}
