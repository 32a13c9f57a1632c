#pragma once
// Timing statistics of a periodic thread (the haptic loop): tick count, missed deadlines,
// and histograms of the period and of the compute time per tick from which percentiles
// are read. record() is O(1) and allocation-free, safe to call every tick; LoopStats is
// trivially copyable (fixed-size arrays only), so a snapshot travels to another thread
// through a TripleBuffer<LoopStats> by plain assignment.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

namespace palpa::engine {

class LoopStats {
 public:
  // Logarithmic bins from kMinTime to kMaxTime, kBinsPerDecade per decade, plus an
  // underflow bin (< kMinTime) and an overflow bin (>= kMaxTime).
  static constexpr int kBinsPerDecade = 20;
  static constexpr int kDecades = 7;
  static constexpr double kMinTime = 1e-7;  // s
  static constexpr double kMaxTime = 1.0;   // s
  static constexpr std::size_t kLogBins = static_cast<std::size_t>(kBinsPerDecade * kDecades);  // 140
  static constexpr std::size_t kBins = kLogBins + 2;
  /// Upper over lower edge of a bin, 10^(1/20): a percentile is at most 12.2 % above the
  /// true value (for values >= kMinTime).
  static constexpr double kBinRatio = 1.1220184543019633;

  /// One tick: the time since the previous tick's start, the time spent computing, and
  /// whether the tick finished late. Times in seconds; negative or NaN ones (a clock
  /// fault) count as 0. O(1), no allocation, no lock, no system call.
  void record(double period_s, double compute_s, bool missed_deadline) noexcept;

  /// Adds another thread's (or another interval's) statistics to these.
  void merge(const LoopStats& other) noexcept;
  void reset() noexcept { *this = LoopStats{}; }

  std::uint64_t ticks() const noexcept { return ticks_; }
  std::uint64_t missed() const noexcept { return missed_; }

  /// The q-quantile (q in [0, 1], clamped; nearest rank) in seconds: the upper edge of the
  /// bin holding it, clamped to the exact max. So it never underestimates, and it
  /// overestimates by less than one bin (a factor kBinRatio) above kMinTime; below
  /// kMinTime it is only bounded by kMinTime. 0 when nothing was recorded.
  double period_percentile(double q) const noexcept { return period_.percentile(q, ticks_); }
  double compute_percentile(double q) const noexcept { return compute_.percentile(q, ticks_); }
  /// Exact. 0 when nothing was recorded.
  double max_period() const noexcept { return period_.max; }
  double max_compute() const noexcept { return compute_.max; }
  /// Exact up to round-off (compensated sum). 0 when nothing was recorded.
  double mean_period() const noexcept { return period_.mean(ticks_); }
  double mean_compute() const noexcept { return compute_.mean(ticks_); }

  /// One readable paragraph: ticks, rate, p50/p99/p99.9/max of period and compute time in
  /// microseconds, missed deadlines and their share. Not for the real-time thread.
  std::string summary() const;

 private:
  struct Histogram {
    std::array<std::uint64_t, kBins> counts{};
    double max = 0.0;
    double sum = 0.0;
    double sum_error = 0.0;  // Neumaier compensation: long runs keep an exact mean

    void add(double seconds) noexcept;
    void merge(const Histogram& other) noexcept;
    double percentile(double q, std::uint64_t n) const noexcept;
    double mean(std::uint64_t n) const noexcept;
  };

  Histogram period_;
  Histogram compute_;
  std::uint64_t ticks_ = 0;
  std::uint64_t missed_ = 0;
};

static_assert(std::is_trivially_copyable_v<LoopStats>, "LoopStats must travel through a TripleBuffer by copy");

}  // namespace palpa::engine
