#include "palpa/engine/loop_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace palpa::engine {
namespace {

// 10^(j/20), j = 0..19: the bin edges within one decade.
constexpr std::array<double, LoopStats::kBinsPerDecade> kDecadeSteps = {
    1.0,
    1.1220184543019633,
    1.2589254117941673,
    1.4125375446227544,
    1.5848931924611136,
    1.7782794100389228,
    1.9952623149688795,
    2.2387211385683394,
    2.51188643150958,
    2.8183829312644537,
    3.1622776601683795,
    3.548133892335755,
    3.9810717055349722,
    4.466835921509632,
    5.011872336272722,
    5.623413251903491,
    6.309573444801933,
    7.079457843841379,
    7.943282347242816,
    8.912509381337454,
};
constexpr std::array<double, LoopStats::kDecades> kDecadeStarts = {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1};

// The kLogBins + 1 edges from kMinTime to kMaxTime; this table, not a logarithm, defines
// the bins, so binning and the reported upper edges agree exactly (1 ms is the lower edge
// of its bin, not a round-off away from it).
constexpr std::array<double, LoopStats::kLogBins + 1> make_edges() {
  std::array<double, LoopStats::kLogBins + 1> edges{};
  for (std::size_t i = 0; i < LoopStats::kLogBins; ++i) {
    edges[i] = kDecadeSteps[i % kDecadeSteps.size()] * kDecadeStarts[i / kDecadeSteps.size()];
  }
  edges[LoopStats::kLogBins] = LoopStats::kMaxTime;
  return edges;
}
constexpr auto kEdges = make_edges();
static_assert(kEdges.front() == LoopStats::kMinTime && kEdges.back() == LoopStats::kMaxTime);

// Histogram index: 0 underflow, 1 + i for [kEdges[i], kEdges[i + 1]), kBins - 1 overflow.
std::size_t bin_of(double seconds) noexcept {
  if (!(seconds >= LoopStats::kMinTime)) return 0;
  // At most 8 comparisons; the first edge above the value is one past its bin.
  return static_cast<std::size_t>(std::upper_bound(kEdges.begin(), kEdges.end(), seconds) - kEdges.begin());
}

// Neumaier's compensated sum: the error stays at round-off however many ticks are added.
void add_compensated(double& sum, double& error, double x) noexcept {
  const double t = sum + x;
  error += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
  sum = t;
}

}  // namespace

void LoopStats::Histogram::add(double seconds) noexcept {
  if (!(seconds > 0.0)) seconds = 0.0;  // negative or NaN: a clock fault, counted as 0
  ++counts[bin_of(seconds)];
  max = std::max(max, seconds);
  add_compensated(sum, sum_error, seconds);
}

void LoopStats::Histogram::merge(const Histogram& other) noexcept {
  for (std::size_t k = 0; k < kBins; ++k) counts[k] += other.counts[k];
  max = std::max(max, other.max);
  add_compensated(sum, sum_error, other.sum);
  sum_error += other.sum_error;
}

double LoopStats::Histogram::percentile(double q, std::uint64_t n) const noexcept {
  if (n == 0) return 0.0;
  q = std::clamp(std::isnan(q) ? 0.0 : q, 0.0, 1.0);
  // Nearest rank: the smallest bin holding at least ceil(q n) values (a hair below q n
  // first, so 0.99 * 1000 is rank 990 whatever its round-off).
  const double rank_real = std::ceil(q * static_cast<double>(n) - 1e-9);
  const std::uint64_t rank = std::max<std::uint64_t>(1, std::min(n, static_cast<std::uint64_t>(std::max(rank_real, 0.0))));
  std::uint64_t seen = 0;
  for (std::size_t k = 0; k < kBins; ++k) {
    seen += counts[k];
    if (seen >= rank) {
      const double upper = k < kBins - 1 ? kEdges[k] : std::numeric_limits<double>::infinity();
      return std::min(upper, max);
    }
  }
  return max;  // not reached while the counts sum to n
}

double LoopStats::Histogram::mean(std::uint64_t n) const noexcept {
  return n == 0 ? 0.0 : (sum + sum_error) / static_cast<double>(n);
}

void LoopStats::record(double period_s, double compute_s, bool missed_deadline) noexcept {
  ++ticks_;
  if (missed_deadline) ++missed_;
  period_.add(period_s);
  compute_.add(compute_s);
}

void LoopStats::merge(const LoopStats& other) noexcept {
  ticks_ += other.ticks_;
  missed_ += other.missed_;
  period_.merge(other.period_);
  compute_.merge(other.compute_);
}

std::string LoopStats::summary() const {
  if (ticks_ == 0) return "No ticks recorded.";
  constexpr double kUs = 1e6;
  const double mean = mean_period();
  const double share = 100.0 * static_cast<double>(missed_) / static_cast<double>(ticks_);
  return fmt::format(
      "{} tick{} at {:.1f} Hz (mean period {:.1f} us). "
      "Period p50 {:.1f} us, p99 {:.1f} us, p99.9 {:.1f} us, max {:.1f} us. "
      "Compute p50 {:.1f} us, p99 {:.1f} us, p99.9 {:.1f} us, max {:.1f} us. "
      "{} missed deadline{} ({:.3g} %). "
      "Percentiles are bin upper edges, at most 12.2 % high.",
      ticks_, ticks_ == 1 ? "" : "s", mean > 0.0 ? 1.0 / mean : 0.0, mean * kUs, period_percentile(0.5) * kUs,
      period_percentile(0.99) * kUs, period_percentile(0.999) * kUs, max_period() * kUs, compute_percentile(0.5) * kUs,
      compute_percentile(0.99) * kUs, compute_percentile(0.999) * kUs, max_compute() * kUs, missed_,
      missed_ == 1 ? "" : "s", share);
}

}  // namespace palpa::engine
