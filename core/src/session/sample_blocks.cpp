#include "sample_blocks.hpp"

#include <zlib.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace palpa::session::detail {
namespace {

// The columns in block order, with their decimal exponent: a value is stored as the integer
// round(value * 10^exponent) (docs/session-format.md, "Units and quantization").
struct Column {
  const char* name;
  int exponent;
};
constexpr std::array<Column, 15> kColumns{{{"tick", 0},
                                           {"t", 6},  // 1 us
                                           {"x", 6},  // 1 um
                                           {"y", 6},
                                           {"z", 6},
                                           {"fx", 3},  // 1 mN
                                           {"fy", 3},
                                           {"fz", 3},
                                           {"body", 0},  // -1: not in contact
                                           {"u", 6},     // 1e-6
                                           {"v", 6},
                                           {"depth", 6},  // 1 um
                                           {"buttons", 0},
                                           {"overrun", 0},
                                           {"fault", 0}}};
constexpr std::size_t kBody = 8;

constexpr double kLargestUnits = 9007199254740992.0;  // 2^53: every integer below is exact as a double

constexpr std::array<double, 10> kPowers{1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

std::int64_t quantize(double value, const Column& column, std::int64_t tick) {
  const double units = value * kPowers[static_cast<std::size_t>(column.exponent)];
  if (!(std::fabs(units) <= kLargestUnits)) {
    throw std::runtime_error(fmt::format("tick {}: column {}: {} does not fit the format's integer units", tick,
                                         column.name, value));
  }
  return std::llround(units);
}

/// The column's integers for every tick of the block (contact columns carry their last
/// value through ticks out of contact: a reader ignores them there, and the deltas stay 0).
std::array<std::vector<std::int64_t>, kColumns.size()> integers_of(const BlockTicks& block) {
  std::array<std::vector<std::int64_t>, kColumns.size()> out;
  for (auto& column : out) column.reserve(block.samples.size());
  std::array<std::int64_t, 3> contact{};  // u, v, depth of the last tick in contact
  for (std::size_t k = 0; k < block.samples.size(); ++k) {
    const auto& s = block.samples[k];
    const std::int64_t tick = block.ticks[k];
    const std::array<double, 7> reals{s.t, s.position[0], s.position[1], s.position[2], s.force[0], s.force[1], s.force[2]};
    out[0].push_back(tick);
    for (std::size_t c = 0; c < reals.size(); ++c) out[c + 1].push_back(quantize(reals[c], kColumns[c + 1], tick));
    out[kBody].push_back(s.body >= 0 ? s.body : -1);
    if (s.body >= 0) {
      contact = {quantize(s.u, kColumns[9], tick), quantize(s.v, kColumns[10], tick),
                 quantize(s.depth, kColumns[11], tick)};
    }
    for (std::size_t c = 0; c < 3; ++c) out[9 + c].push_back(contact[c]);
    out[12].push_back(s.buttons);
    out[13].push_back(s.overrun ? 1 : 0);
    out[14].push_back(s.fault ? 1 : 0);
  }
  return out;
}

/// Differences of order `order` (first values kept): undone by `order` running sums.
std::vector<std::int64_t> differences(std::vector<std::int64_t> values, int order) {
  for (int pass = 0; pass < order; ++pass) {
    for (std::size_t k = values.size(); k-- > 1;) values[k] -= values[k - 1];
  }
  return values;
}

int width_for(const std::vector<std::int64_t>& residuals, std::size_t from) {
  std::int64_t lo = 0, hi = 0;
  for (std::size_t k = from; k < residuals.size(); ++k) {
    lo = std::min(lo, residuals[k]);
    hi = std::max(hi, residuals[k]);
  }
  if (lo == 0 && hi == 0) return 0;
  if (lo >= -128 && hi <= 127) return 1;
  if (lo >= -32768 && hi <= 32767) return 2;
  if (lo >= std::numeric_limits<std::int32_t>::min() && hi <= std::numeric_limits<std::int32_t>::max()) return 4;
  return 8;
}

void put_le(std::string& out, std::int64_t value, int width) {
  auto bits = static_cast<std::uint64_t>(value);
  for (int b = 0; b < width; ++b, bits >>= 8) out.push_back(static_cast<char>(bits & 0xFF));
}

/// One column: order, width, exponent (one byte each), the first min(order, n) residuals as
/// 8-byte integers, the others in `width` bytes; all little-endian, signed.
void put_column(std::string& out, const std::vector<std::int64_t>& values, int exponent) {
  // The order whose residuals are smallest in total: 2 for smooth motion, 1 for steps.
  std::vector<std::int64_t> best;
  int best_order = 0;
  std::uint64_t best_cost = std::numeric_limits<std::uint64_t>::max();
  for (int order = 0; order <= 2; ++order) {
    auto residuals = differences(values, order);
    std::uint64_t cost = 0;
    for (std::size_t k = static_cast<std::size_t>(order); k < residuals.size(); ++k) {
      cost += static_cast<std::uint64_t>(residuals[k] < 0 ? -residuals[k] : residuals[k]);
    }
    if (cost < best_cost) {
      best_cost = cost;
      best_order = order;
      best = std::move(residuals);
    }
  }
  const std::size_t head = std::min<std::size_t>(static_cast<std::size_t>(best_order), best.size());
  const int width = width_for(best, head);
  out.push_back(static_cast<char>(best_order));
  out.push_back(static_cast<char>(width));
  out.push_back(static_cast<char>(exponent));
  for (std::size_t k = 0; k < head; ++k) put_le(out, best[k], 8);
  for (std::size_t k = head; k < best.size(); ++k) put_le(out, best[k], width);
}

}  // namespace

std::string encode_block(const BlockTicks& block) {
  const auto columns = integers_of(block);
  std::string raw;
  raw.reserve(block.samples.size() * kColumns.size() * 2);
  for (std::size_t c = 0; c < kColumns.size(); ++c) put_column(raw, columns[c], kColumns[c].exponent);
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(size, '\0');
  const int rc = compress2(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                           static_cast<uLong>(raw.size()), Z_BEST_COMPRESSION);
  if (rc != Z_OK) throw std::runtime_error(fmt::format("zlib cannot compress a block ({})", zError(rc)));
  packed.resize(size);
  return packed;
}

namespace {

/// Reads the columns of an inflated block; every read is bounds-checked.
class ColumnReader {
 public:
  ColumnReader(const unsigned char* data, std::size_t size) : at_(data), end_(data + size) {}

  /// The column's integers, running sums undone; its exponent in `exponent`.
  void read(const Column& column, std::int64_t count, std::vector<std::int64_t>& values, int& exponent) {
    const int order = byte(column);
    const int width = byte(column);
    exponent = byte(column);
    if (order > 2) throw std::runtime_error(fmt::format("column {}: delta order {} (0, 1 or 2)", column.name, order));
    if (width != 0 && width != 1 && width != 2 && width != 4 && width != 8) {
      throw std::runtime_error(fmt::format("column {}: integer width {} (0, 1, 2, 4 or 8 bytes)", column.name, width));
    }
    if (exponent >= static_cast<int>(kPowers.size())) {
      throw std::runtime_error(fmt::format("column {}: decimal exponent {} (0 to 9)", column.name, exponent));
    }
    const auto n = static_cast<std::size_t>(count);
    const std::size_t head = std::min<std::size_t>(static_cast<std::size_t>(order), n);
    values.resize(n);
    need(column, head * 8 + (n - head) * static_cast<std::size_t>(width));
    for (std::size_t k = 0; k < head; ++k) values[k] = take(8);
    switch (width) {
      case 0: std::fill(values.begin() + static_cast<std::ptrdiff_t>(head), values.end(), 0); break;
      case 1: widen<std::int8_t>(values, head); break;
      case 2: widen<std::int16_t>(values, head); break;
      case 4: widen<std::int32_t>(values, head); break;
      default: widen<std::int64_t>(values, head);
    }
    // Running sums in unsigned arithmetic: a hostile block wraps around instead of overflowing.
    for (int pass = 0; pass < order; ++pass) {
      std::uint64_t sum = 0;
      for (auto& v : values) v = static_cast<std::int64_t>(sum += static_cast<std::uint64_t>(v));
    }
  }
  std::size_t left() const { return static_cast<std::size_t>(end_ - at_); }

 private:
  void need(const Column& column, std::size_t bytes) const {
    if (bytes > left()) throw std::runtime_error(fmt::format("column {}: the block ends inside it", column.name));
  }
  int byte(const Column& column) {
    need(column, 1);
    return *at_++;
  }
  // values[head...] from consecutive little-endian integers of type T.
  template <typename T>
  void widen(std::vector<std::int64_t>& values, std::size_t head) {
    for (std::size_t k = head; k < values.size(); ++k, at_ += sizeof(T)) {
      T v;
      if constexpr (std::endian::native == std::endian::little) {
        std::memcpy(&v, at_, sizeof(T));
      } else {
        v = static_cast<T>(peek(sizeof(T)));
      }
      values[k] = v;
    }
  }
  // A little-endian signed integer of `width` bytes (2, 4 or 8).
  std::int64_t peek(std::size_t width) const {
    std::uint64_t bits = 0;
    for (std::size_t b = 0; b < width; ++b) bits |= static_cast<std::uint64_t>(at_[b]) << (8 * b);
    const auto unused = static_cast<int>(64 - 8 * width);
    return static_cast<std::int64_t>(bits << unused) >> unused;  // sign-extended
  }
  std::int64_t take(std::size_t width) {
    const std::int64_t value = peek(width);
    at_ += width;
    return value;
  }
  const unsigned char* at_;
  const unsigned char* end_;
};

std::vector<unsigned char>& inflate_block(const void* data, std::size_t size, std::int64_t count) {
  thread_local std::vector<unsigned char> raw;
  // The largest a block of `count` ticks can be: every column 8 bytes wide.
  const std::size_t bound = kColumns.size() * (3 + 2 * 8 + static_cast<std::size_t>(count) * 8);
  raw.resize(bound);
  uLongf n = static_cast<uLongf>(bound);
  const int rc = uncompress(raw.data(), &n, static_cast<const Bytef*>(data), static_cast<uLong>(size));
  if (rc == Z_BUF_ERROR) {
    throw std::runtime_error(fmt::format("larger than a block of {} ticks can be, or cut short", count));
  }
  if (rc != Z_OK) throw std::runtime_error(fmt::format("damaged block (zlib: {})", zError(rc)));
  raw.resize(n);
  return raw;
}

}  // namespace

void decode_block(const void* data, std::size_t size, std::int64_t count, std::vector<std::int64_t>& ticks,
                  std::vector<engine::Sample>& out) {
  if (count < 1 || count > kMaxBlockTicks) {
    throw std::runtime_error(fmt::format("count {} (a block holds 1 to {} ticks)", count, kMaxBlockTicks));
  }
  const auto& raw = inflate_block(data, size, count);
  ColumnReader reader(raw.data(), raw.size());
  thread_local std::array<std::vector<std::int64_t>, kColumns.size()> ints;
  std::array<double, kColumns.size()> scale{};
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    int exponent = 0;
    reader.read(kColumns[c], count, ints[c], exponent);
    scale[c] = kPowers[static_cast<std::size_t>(exponent)];
  }
  if (reader.left() != 0) throw std::runtime_error(fmt::format("{} bytes left over after the columns", reader.left()));
  const auto range = [&](std::size_t c, std::size_t k, std::int64_t lo, std::int64_t hi) {
    const std::int64_t value = ints[c][k];
    if (value < lo || value > hi || scale[c] != 1.0) {
      throw std::runtime_error(fmt::format("tick {}: column {}: {} (an integer in {}..{})", ints[0][k],
                                           kColumns[c].name, static_cast<double>(value) / scale[c], lo, hi));
    }
    return value;
  };
  const auto n = static_cast<std::size_t>(count);  // `out` grows geometrically: no reserve per block
  for (std::size_t k = 0; k < n; ++k) {
    engine::Sample s;
    // Divided, not multiplied by 10^-e: a value written as a short decimal reads back as
    // exactly the double it was (7 / 1000.0 s, stored as 7000 us, reads back as 7 / 1000.0).
    s.t = static_cast<double>(ints[1][k]) / scale[1];
    for (std::size_t a = 0; a < 3; ++a) {
      s.position[a] = static_cast<double>(ints[2 + a][k]) / scale[2 + a];
      s.force[a] = static_cast<double>(ints[5 + a][k]) / scale[5 + a];
    }
    s.body = static_cast<std::int32_t>(range(kBody, k, -1, std::numeric_limits<std::int32_t>::max()));
    if (s.body >= 0) {
      s.u = static_cast<double>(ints[9][k]) / scale[9];
      s.v = static_cast<double>(ints[10][k]) / scale[10];
      s.depth = static_cast<double>(ints[11][k]) / scale[11];
    }
    s.buttons = static_cast<std::uint32_t>(range(12, k, 0, std::numeric_limits<std::uint32_t>::max()));
    s.overrun = range(13, k, 0, 1) != 0;
    s.fault = range(14, k, 0, 1) != 0;
    out.push_back(s);
  }
  ticks.insert(ticks.end(), ints[0].begin(), ints[0].begin() + static_cast<std::ptrdiff_t>(n));
}

}  // namespace palpa::session::detail
