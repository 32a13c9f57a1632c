// The engine's real-time building blocks: the SPSC queue and the triple buffer with a
// producer (writer) and a consumer (reader) thread at once (every value exactly once and
// in order; drops counted exactly; no torn, older or lost snapshot), their edge cases
// against a single-threaded model, and LoopStats against hand-computed statistics and bin
// edges computed here as 1e-7 * 10^(k/20).
#include "palpa/engine/loop_stats.hpp"
#include "palpa/engine/spsc_queue.hpp"
#include "palpa/engine/triple_buffer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace palpa::engine {
namespace {

// The threaded loops run 10x shorter without NDEBUG (the debug + sanitizer build).
#ifdef NDEBUG
constexpr std::uint64_t kLoopDivisor = 1;
#else
constexpr std::uint64_t kLoopDivisor = 10;
#endif

// A stuck thread fails its test instead of hanging the suite.
constexpr auto kDeadline = std::chrono::seconds(30);

// Two words that must agree: a torn copy shows.
struct Item {
  std::uint64_t seq = 0;
  std::uint64_t check = 0;
};
Item make_item(std::uint64_t seq) { return {seq, ~seq}; }

// =======================================================================================
// SpscQueue

static_assert(SpscQueue<int, 8>::capacity() == 8);
static_assert(SpscQueue<Item, 1>::capacity() == 1);
static_assert(alignof(SpscQueue<int, 8>) == 64);  // head and tail on cache lines of their own

TEST(SpscQueue, EmptyAndFullEdges) {
  SpscQueue<int, 4> q;
  EXPECT_EQ(q.size_approx(), 0u);
  int out = -7;
  EXPECT_FALSE(q.try_pop(out));
  EXPECT_EQ(out, -7);  // untouched on failure

  for (int v = 0; v < 4; ++v) EXPECT_TRUE(q.try_push(v));
  EXPECT_EQ(q.size_approx(), 4u);
  EXPECT_FALSE(q.try_push(4));  // full: refused, nothing overwritten
  EXPECT_EQ(q.size_approx(), 4u);

  ASSERT_TRUE(q.try_pop(out));
  EXPECT_EQ(out, 0);
  EXPECT_TRUE(q.try_push(4));  // one free slot again, then full again
  EXPECT_FALSE(q.try_push(5));
  for (int want = 1; want <= 4; ++want) {
    ASSERT_TRUE(q.try_pop(out));
    EXPECT_EQ(out, want);
  }
  EXPECT_EQ(q.size_approx(), 0u);
  out = -7;
  EXPECT_FALSE(q.try_pop(out));
  EXPECT_EQ(out, -7);
}

TEST(SpscQueue, CapacityOneAlternatesFullAndEmpty) {
  SpscQueue<Item, 1> q;
  Item out;
  for (std::uint64_t k = 0; k < 1000; ++k) {
    ASSERT_TRUE(q.try_push(make_item(k)));
    ASSERT_FALSE(q.try_push(make_item(k + 1000)));
    ASSERT_EQ(q.size_approx(), 1u);
    ASSERT_TRUE(q.try_pop(out));
    ASSERT_EQ(out.seq, k);
    ASSERT_EQ(out.check, ~k);
    ASSERT_FALSE(q.try_pop(out));
  }
}

TEST(SpscQueue, MatchesADequeThroughManyWrapArounds) {
  // Random bursts of pushes and pops, single-threaded, against std::deque capped at the
  // capacity: the indices wrap around the 8 slots thousands of times.
  SpscQueue<Item, 8> q;
  std::deque<std::uint64_t> model;
  std::mt19937_64 rng(7);
  std::uint64_t next = 0;
  for (int step = 0; step < 20000; ++step) {
    const auto burst = static_cast<int>(rng() % 11);
    if (rng() % 2 == 0) {
      for (int k = 0; k < burst; ++k) {
        const bool pushed = q.try_push(make_item(next));
        ASSERT_EQ(pushed, model.size() < 8);
        if (pushed) model.push_back(next);
        ++next;
      }
    } else {
      for (int k = 0; k < burst; ++k) {
        Item out;
        const bool popped = q.try_pop(out);
        ASSERT_EQ(popped, !model.empty());
        if (!popped) continue;
        ASSERT_EQ(out.seq, model.front());
        ASSERT_EQ(out.check, ~model.front());
        model.pop_front();
      }
    }
    ASSERT_EQ(q.size_approx(), model.size());
  }
  EXPECT_GT(next, 8u * 1000u);
}

TEST(SpscQueue, StressEveryValueArrivesOnceInOrder) {
  // A producer and a consumer thread move 10^6 sequence numbers through 64 slots; both
  // retry (yielding) when full or empty.
  const std::uint64_t n = 1'000'000 / kLoopDivisor;
  SpscQueue<Item, 64> q;
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;

  std::thread producer([&] {
    for (std::uint64_t i = 0; i < n; ++i) {
      while (!q.try_push(make_item(i))) {
        if (std::chrono::steady_clock::now() > deadline) return;
        std::this_thread::yield();
      }
    }
  });

  std::uint64_t received = 0;
  std::uint64_t out_of_order = 0;
  std::uint64_t torn = 0;
  std::uint64_t oversize = 0;
  while (received < n && std::chrono::steady_clock::now() < deadline) {
    Item out;
    if (!q.try_pop(out)) {
      std::this_thread::yield();
      continue;
    }
    if (out.seq != received) ++out_of_order;
    if (out.check != ~out.seq) ++torn;
    if (q.size_approx() > q.capacity()) ++oversize;
    ++received;
  }
  producer.join();

  EXPECT_EQ(received, n);
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(oversize, 0u);
  Item extra;
  EXPECT_FALSE(q.try_pop(extra));  // nothing duplicated
}

TEST(SpscQueue, DropsCountedExactlyWhenTheConsumerIsSlower) {
  // The producer tries each value once and counts refusals, like the haptic thread logging
  // samples; it works a little per value, the consumer four times as much. The consumer
  // starts only after 2 x capacity attempts (so at least `capacity` drops are certain), and
  // the producer goes on until the consumer has taken a good number of values, so the two
  // really overlap however the threads are scheduled.
  constexpr std::size_t kCapacity = 16;
  const std::uint64_t min_attempts = 100'000 / kLoopDivisor;
  const std::uint64_t min_received = 5'000 / kLoopDivisor;
  SpscQueue<Item, kCapacity> q;
  std::vector<std::uint8_t> accepted;  // written by the producer only (read after join)
  accepted.reserve(4 * min_attempts);
  std::uint64_t drops = 0;  // likewise
  std::atomic<std::uint64_t> received_count{0};
  std::atomic<bool> consumer_may_start{false};
  std::atomic<bool> producer_done{false};
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;

  std::thread producer([&] {
    volatile std::uint64_t work = 0;
    for (std::uint64_t i = 0; i < min_attempts || received_count.load(std::memory_order_relaxed) < min_received;
         ++i) {
      if (std::chrono::steady_clock::now() > deadline) break;
      const bool pushed = q.try_push(make_item(i));
      accepted.push_back(pushed ? 1 : 0);
      if (!pushed) ++drops;
      if (i + 1 == 2 * kCapacity) consumer_may_start.store(true, std::memory_order_release);
      for (int k = 0; k < 16; ++k) work = work + 1;
      if (i % 256 == 255) std::this_thread::yield();  // lets a consumer sharing the core run
    }
    consumer_may_start.store(true, std::memory_order_release);
    producer_done.store(true, std::memory_order_release);
  });

  std::vector<std::uint64_t> received;
  received.reserve(4 * min_attempts);
  std::uint64_t torn = 0;
  volatile std::uint64_t work = 0;
  while (!consumer_may_start.load(std::memory_order_acquire)) std::this_thread::yield();
  for (;;) {
    // Read the flag before draining: once it is set every push is visible to the drain.
    const bool finished = producer_done.load(std::memory_order_acquire);
    Item out;
    bool any = false;
    while (q.try_pop(out)) {
      any = true;
      if (out.check != ~out.seq) ++torn;
      received.push_back(out.seq);
      received_count.store(received.size(), std::memory_order_relaxed);
      for (int k = 0; k < 64; ++k) work = work + 1;  // the slow part
    }
    if (finished || std::chrono::steady_clock::now() > deadline) break;
    if (!any) std::this_thread::yield();
  }
  producer.join();

  const std::uint64_t attempts = accepted.size();
  EXPECT_GE(attempts, min_attempts);
  EXPECT_GE(received.size(), min_received);
  EXPECT_GE(drops, kCapacity);
  EXPECT_EQ(received.size() + drops, attempts);
  EXPECT_EQ(torn, 0u);
  std::vector<std::uint64_t> expected;
  for (std::uint64_t i = 0; i < attempts; ++i) {
    if (accepted[i] != 0) expected.push_back(i);
  }
  EXPECT_TRUE(received == expected) << "the consumer must get exactly the accepted values, in order";
}

// =======================================================================================
// TripleBuffer

TEST(TripleBuffer, ReaderSeesTheInitialValueThenOnlyTheNewest) {
  TripleBuffer<int> b(7);
  EXPECT_EQ(b.read(), 7);
  EXPECT_FALSE(b.update());
  EXPECT_EQ(b.read(), 7);

  b.write_slot() = 1;
  b.publish();
  b.write_slot() = 2;
  b.publish();
  EXPECT_TRUE(b.update());
  EXPECT_EQ(b.read(), 2);  // 1 was overtaken before the reader looked
  EXPECT_FALSE(b.update());
  EXPECT_EQ(b.read(), 2);

  b.write_slot() = 3;
  b.publish();
  EXPECT_EQ(b.read(), 2);  // unchanged until update()
  EXPECT_TRUE(b.update());
  EXPECT_EQ(b.read(), 3);
}

TEST(TripleBuffer, WriterAndReaderNeverShareASlot) {
  TripleBuffer<int> b(0);
  std::mt19937 rng(3);
  int published = 0;
  for (int step = 0; step < 1000; ++step) {
    ASSERT_NE(&b.write_slot(), &b.read());
    if (rng() % 2 == 0) {
      b.write_slot() = ++published;
      b.publish();
    } else if (b.update()) {
      ASSERT_EQ(b.read(), published);
    }
  }
}

TEST(TripleBuffer, VectorValuesReuseTheirStorage) {
  // Slots are copies of the initial value, sized once; writing into them never reallocates:
  // the writer and the reader only ever see the three original buffers.
  TripleBuffer<std::vector<double>> b(std::vector<double>(1000, 0.0));
  std::set<const double*> buffers;
  for (int k = 1; k <= 100; ++k) {
    auto& slot = b.write_slot();
    ASSERT_EQ(slot.size(), 1000u);
    std::fill(slot.begin(), slot.end(), static_cast<double>(k));
    buffers.insert(slot.data());
    b.publish();
    if (k % 3 == 0) {
      ASSERT_TRUE(b.update());
      EXPECT_EQ(b.read().front(), static_cast<double>(k));
      buffers.insert(b.read().data());
    }
  }
  EXPECT_EQ(buffers.size(), 3u);
}

// All fields equal to the publish counter: fields that differ mean a torn read.
struct Snapshot {
  std::array<std::uint64_t, 32> fields{};
};

// The writer publishes at least `min_publishes` values and goes on until the reader has
// taken `min_updates` of them, yielding now and then, so the two overlap however the
// threads are scheduled; then it tells the reader its last value.
struct Overlap {
  std::uint64_t min_publishes = 0;
  std::uint64_t min_updates = 0;
  std::atomic<std::uint64_t> updates{0};  // the reader's count
  std::atomic<std::uint64_t> last{0};     // the writer's last value, 0 while writing
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::now() + kDeadline;

  bool writer_goes_on(std::uint64_t published) const {
    if (published % 64 == 0) std::this_thread::yield();
    if (std::chrono::steady_clock::now() > deadline) return false;
    return published < min_publishes || updates.load(std::memory_order_relaxed) < min_updates;
  }
};

TEST(TripleBuffer, ConcurrentReaderNeverSeesATornOrOlderValueAndSeesTheLast) {
  TripleBuffer<Snapshot> b{Snapshot{}};
  Overlap overlap;
  overlap.min_publishes = 200'000 / kLoopDivisor;
  overlap.min_updates = 2'000 / kLoopDivisor;

  std::thread writer([&] {
    std::uint64_t c = 0;
    while (overlap.writer_goes_on(c)) {
      ++c;
      auto& s = b.write_slot();
      for (auto& f : s.fields) f = c;
      b.publish();
    }
    overlap.last.store(c, std::memory_order_release);
  });

  std::uint64_t last = 0;
  std::uint64_t updates = 0;
  std::uint64_t torn = 0;
  std::uint64_t not_newer = 0;
  std::uint64_t changed_without_update = 0;
  std::uint64_t final_value = 0;
  for (std::uint64_t polls = 1;; ++polls) {
    final_value = overlap.last.load(std::memory_order_acquire);  // before update(): then it is seen
    const bool fresh = b.update();
    const Snapshot& s = b.read();
    const std::uint64_t c = s.fields[0];
    if (!std::all_of(s.fields.begin(), s.fields.end(), [c](std::uint64_t f) { return f == c; })) ++torn;
    if (fresh) {
      overlap.updates.store(++updates, std::memory_order_relaxed);
      if (c <= last) ++not_newer;  // each taken value is strictly newer than the one before
      last = c;
    } else if (c != last) {
      ++changed_without_update;
    }
    if (final_value != 0 && last == final_value) break;
    if (std::chrono::steady_clock::now() > overlap.deadline) break;
    if (!fresh && polls % 64 == 0) std::this_thread::yield();
  }
  writer.join();

  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(not_newer, 0u);
  EXPECT_EQ(changed_without_update, 0u);
  EXPECT_GE(final_value, overlap.min_publishes);
  EXPECT_EQ(last, final_value);  // the last value was eventually seen
  EXPECT_GE(updates, overlap.min_updates);
  EXPECT_FALSE(b.update());  // and nothing newer is left
}

TEST(TripleBuffer, CarriesConsistentLoopStatsSnapshots) {
  // The haptic thread's pattern: record a tick, copy the whole LoopStats into the write
  // slot, publish. Every snapshot the reader takes must be one whole tick's state.
  TripleBuffer<LoopStats> b{LoopStats{}};
  Overlap overlap;
  overlap.min_publishes = 20'000 / kLoopDivisor;
  overlap.min_updates = 1'000 / kLoopDivisor;
  const auto compute_of = [](std::uint64_t tick) { return static_cast<double>(tick) * 1e-7; };

  std::thread writer([&] {
    LoopStats stats;
    while (overlap.writer_goes_on(stats.ticks())) {
      const std::uint64_t t = stats.ticks() + 1;
      stats.record(1e-3, compute_of(t), t % 3 == 0);
      b.write_slot() = stats;
      b.publish();
    }
    overlap.last.store(stats.ticks(), std::memory_order_release);
  });

  std::uint64_t last = 0;
  std::uint64_t updates = 0;
  std::uint64_t inconsistent = 0;
  std::uint64_t final_value = 0;
  for (std::uint64_t polls = 1;; ++polls) {
    final_value = overlap.last.load(std::memory_order_acquire);
    if (b.update()) {
      overlap.updates.store(++updates, std::memory_order_relaxed);
      const LoopStats& s = b.read();
      const std::uint64_t t = s.ticks();
      if (t <= last || s.missed() != t / 3 || s.max_compute() != compute_of(t) ||
          s.compute_percentile(1.0) != compute_of(t) || s.max_period() != 1e-3 ||
          std::abs(s.mean_period() - 1e-3) > 1e-15) {
        ++inconsistent;
      }
      last = t;
    } else if (polls % 64 == 0) {
      std::this_thread::yield();
    }
    if (final_value != 0 && last == final_value) break;
    if (std::chrono::steady_clock::now() > overlap.deadline) break;
  }
  writer.join();
  EXPECT_EQ(inconsistent, 0u);
  EXPECT_GE(updates, overlap.min_updates);
  EXPECT_GE(final_value, overlap.min_publishes);
  EXPECT_EQ(last, final_value);
}

// =======================================================================================
// LoopStats

// The upper edge of the logarithmic bin k (0-based from 100 ns), computed independently.
double upper_edge(int k) { return 1e-7 * std::pow(10.0, (k + 1) / 20.0); }
// The 0-based logarithmic bin holding t (t in [100 ns, 1 s), away from edges).
int bin_index(double t) { return static_cast<int>(std::floor(20.0 * std::log10(t / 1e-7))); }

constexpr double kRatio = 1.1220184543019634;  // 10^(1/20)

static_assert(std::is_trivially_copyable_v<LoopStats>);
static_assert(noexcept(std::declval<LoopStats&>().record(0.0, 0.0, false)));

TEST(LoopStats, EmptyIsAllZero) {
  const LoopStats s;
  EXPECT_EQ(s.ticks(), 0u);
  EXPECT_EQ(s.missed(), 0u);
  EXPECT_EQ(s.period_percentile(0.5), 0.0);
  EXPECT_EQ(s.compute_percentile(0.99), 0.0);
  EXPECT_EQ(s.max_period(), 0.0);
  EXPECT_EQ(s.max_compute(), 0.0);
  EXPECT_EQ(s.mean_period(), 0.0);
  EXPECT_EQ(s.summary(), "No ticks recorded.");
}

LoopStats thousand_at_1ms_ten_at_2ms() {
  LoopStats s;
  for (int k = 0; k < 1000; ++k) s.record(1e-3, 200e-6, false);
  for (int k = 0; k < 10; ++k) s.record(2e-3, 900e-6, true);
  return s;
}

TEST(LoopStats, HandComputedPercentilesMaxMeanAndMisses) {
  const LoopStats s = thousand_at_1ms_ten_at_2ms();
  EXPECT_EQ(s.ticks(), 1010u);
  EXPECT_EQ(s.missed(), 10u);

  // Ranks (nearest rank, ceil(q n)): p50 505 and p99 1000 are 1 ms, p99.9 1009 is 2 ms.
  // 1 ms is the lower edge of bin 80 exactly, so its bin reports 10^(81/20) * 100 ns.
  EXPECT_NEAR(s.period_percentile(0.5), upper_edge(80), 1e-15);
  EXPECT_NEAR(s.period_percentile(0.99), upper_edge(80), 1e-15);
  // 2 ms lies in bin 86 = [1.995, 2.239) ms; the edge is clamped to the exact max.
  EXPECT_EQ(bin_index(2e-3), 86);
  EXPECT_GE(s.period_percentile(0.999), 2e-3);
  EXPECT_LE(s.period_percentile(0.999), upper_edge(86));
  EXPECT_EQ(s.period_percentile(0.999), 2e-3);
  EXPECT_EQ(s.period_percentile(1.0), 2e-3);

  EXPECT_EQ(s.max_period(), 2e-3);
  EXPECT_EQ(s.max_compute(), 900e-6);
  EXPECT_DOUBLE_EQ(s.mean_period(), (1000 * 1e-3 + 10 * 2e-3) / 1010.0);
  EXPECT_DOUBLE_EQ(s.mean_compute(), (1000 * 200e-6 + 10 * 900e-6) / 1010.0);

  EXPECT_NEAR(s.compute_percentile(0.5), upper_edge(bin_index(200e-6)), 1e-15);
  EXPECT_EQ(s.compute_percentile(0.999), 900e-6);
}

TEST(LoopStats, PercentileIsTheBinUpperEdgeAtMost12PercentHigh) {
  // Log-uniform times over the whole range, each with a 5 s companion (overflow) so the
  // percentile of rank 1 is its bin's edge, not the clamped max.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> exponent(-7.0, 0.0);
  double worst = 1.0;
  for (int k = 0; k < 2000; ++k) {
    const double t = std::pow(10.0, exponent(rng));
    LoopStats s;
    s.record(t, t, false);
    s.record(5.0, 5.0, false);
    const double p = s.period_percentile(0.5);
    ASSERT_GT(p, t);
    ASSERT_LE(p, t * kRatio * (1.0 + 1e-12));
    // p is an edge 100 ns * 10^(j/20).
    const double j = 20.0 * std::log10(p / 1e-7);
    ASSERT_NEAR(j, std::round(j), 1e-9) << "t = " << t;
    ASSERT_EQ(s.compute_percentile(0.5), p);
    ASSERT_EQ(s.period_percentile(1.0), 5.0);  // overflow: the exact max
    worst = std::max(worst, p / t);
  }
  EXPECT_GT(worst, 1.11);  // the bins are as coarse as stated, not finer

  // Exact decades are lower edges: 100 ns ... 100 ms report one bin ratio above.
  for (const double t : {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1}) {  // literals: pow is an ulp off
    LoopStats s;
    s.record(t, t, false);
    s.record(5.0, 5.0, false);
    EXPECT_NEAR(s.period_percentile(0.5) / t, kRatio, 1e-12) << "t = " << t;
  }
}

TEST(LoopStats, UnderflowOverflowAndClockFaults) {
  LoopStats s;
  s.record(50e-9, 3.0, false);  // below 100 ns; compute above 1 s
  s.record(3.0, 50e-9, false);
  EXPECT_EQ(s.period_percentile(0.5), 1e-7);  // the underflow bin's upper edge
  EXPECT_EQ(s.period_percentile(1.0), 3.0);   // overflow: the exact max
  EXPECT_EQ(s.compute_percentile(0.5), 1e-7);
  EXPECT_EQ(s.max_compute(), 3.0);

  LoopStats one;
  one.record(50e-9, 50e-9, false);
  EXPECT_EQ(one.period_percentile(0.5), 50e-9);  // clamped to the max: never above it

  LoopStats faults;  // negative and NaN times count as 0
  faults.record(-1.0, std::numeric_limits<double>::quiet_NaN(), true);
  EXPECT_EQ(faults.ticks(), 1u);
  EXPECT_EQ(faults.missed(), 1u);
  EXPECT_EQ(faults.max_period(), 0.0);
  EXPECT_EQ(faults.mean_compute(), 0.0);
  EXPECT_EQ(faults.period_percentile(0.5), 0.0);
}

TEST(LoopStats, QuantileEndsAndClamping) {
  LoopStats s;
  for (int k = 1; k <= 100; ++k) s.record(k * 1e-5, 1e-6, false);  // 10 us ... 1 ms
  EXPECT_NEAR(s.period_percentile(0.0), upper_edge(bin_index(1e-5)), 1e-18);  // rank 1
  EXPECT_EQ(s.period_percentile(-3.0), s.period_percentile(0.0));
  EXPECT_EQ(s.period_percentile(std::numeric_limits<double>::quiet_NaN()), s.period_percentile(0.0));
  EXPECT_EQ(s.period_percentile(1.0), 1e-3);
  EXPECT_EQ(s.period_percentile(7.0), 1e-3);
  // Rank 50 is 0.5 ms; rank 51 is 0.51 ms, in the next bin up (0.501 ... 0.562 ms).
  EXPECT_NEAR(s.period_percentile(0.5), upper_edge(bin_index(5e-4)), 1e-15);
  EXPECT_NEAR(s.period_percentile(0.51), upper_edge(bin_index(5.1e-4)), 1e-15);
  EXPECT_EQ(bin_index(5e-4) + 1, bin_index(5.1e-4));
}

TEST(LoopStats, MergeEqualsRecordingEverythingAndResetEmpties) {
  std::mt19937_64 rng(5);
  std::lognormal_distribution<double> period(std::log(1e-3), 0.3);
  std::lognormal_distribution<double> compute(std::log(1e-4), 0.8);
  LoopStats a;
  LoopStats b;
  LoopStats all;
  for (int k = 0; k < 3000; ++k) {
    const double p = period(rng);
    const double c = compute(rng);
    const bool late = c > 3e-4;
    (k % 3 == 0 ? a : b).record(p, c, late);
    all.record(p, c, late);
  }
  a.merge(b);
  EXPECT_EQ(a.ticks(), all.ticks());
  EXPECT_EQ(a.missed(), all.missed());
  EXPECT_GT(a.missed(), 0u);
  for (const double q : {0.0, 0.1, 0.5, 0.9, 0.99, 0.999, 1.0}) {
    EXPECT_EQ(a.period_percentile(q), all.period_percentile(q)) << q;
    EXPECT_EQ(a.compute_percentile(q), all.compute_percentile(q)) << q;
  }
  EXPECT_EQ(a.max_period(), all.max_period());
  EXPECT_EQ(a.max_compute(), all.max_compute());
  EXPECT_DOUBLE_EQ(a.mean_period(), all.mean_period());
  EXPECT_DOUBLE_EQ(a.mean_compute(), all.mean_compute());

  const LoopStats copy = a;  // trivially copyable: a snapshot is a plain copy
  EXPECT_EQ(copy.summary(), a.summary());

  a.reset();
  EXPECT_EQ(a.ticks(), 0u);
  EXPECT_EQ(a.missed(), 0u);
  EXPECT_EQ(a.max_period(), 0.0);
  EXPECT_EQ(a.period_percentile(0.5), 0.0);
  EXPECT_EQ(a.summary(), "No ticks recorded.");
}

TEST(LoopStats, LongRunMeanStaysExact) {
  // 10^6 ticks of 0.1 ms: a plain running sum drifts by many ulps, the compensated one not.
  const std::uint64_t n = 1'000'000 / kLoopDivisor;
  LoopStats s;
  for (std::uint64_t k = 0; k < n; ++k) s.record(1e-4, 3e-5, false);
  EXPECT_EQ(s.ticks(), n);
  EXPECT_DOUBLE_EQ(s.mean_period(), 1e-4);
  EXPECT_DOUBLE_EQ(s.mean_compute(), 3e-5);
}

TEST(LoopStats, SummaryIsOneReadableParagraph) {
  const std::string text = thousand_at_1ms_ten_at_2ms().summary();
  // Rate 1010 / 1.02 s; mean period 1.0099 ms; p50 the 1 ms bin's upper edge 1122.0 us.
  for (const char* part : {"1010 ticks", "990.2 Hz", "mean period 1009.9 us", "Period p50 1122.0 us",
                           "p99.9 2000.0 us", "max 2000.0 us", "Compute p50 ", "max 900.0 us",
                           "10 missed deadlines (0.99 %)"}) {
    EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in: " << text;
  }
  EXPECT_EQ(text.find('\n'), std::string::npos);

  LoopStats one;
  one.record(1e-3, 1e-4, true);
  EXPECT_NE(one.summary().find("1 tick at 1000.0 Hz"), std::string::npos) << one.summary();
  EXPECT_NE(one.summary().find("1 missed deadline (100 %)"), std::string::npos) << one.summary();
}

}  // namespace
}  // namespace palpa::engine
