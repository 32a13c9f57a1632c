#pragma once
// The compact sample blocks of session format 2 (docs/session-format.md, "sample_blocks"):
// up to kBlockTicks consecutive ticks per block, each column as integers in a fixed decimal
// unit, delta-coded, stored in the smallest integer width that holds the block's residuals,
// the whole block zlib-compressed. Internal to core/session.
#include <cstdint>
#include <string>
#include <vector>

#include "palpa/engine/engine.hpp"

namespace palpa::session::detail {

/// Ticks per block: about a second at 1 kHz; large enough that zlib and the column headers
/// cost little, small enough that a block decodes in the cache.
inline constexpr std::int64_t kBlockTicks = 1024;
/// The most ticks a block may declare (a hostile count must not size a huge buffer).
inline constexpr std::int64_t kMaxBlockTicks = 65536;

/// One block's ticks: `ticks[k]` is the tick number of `samples[k]`.
struct BlockTicks {
  std::vector<std::int64_t> ticks;
  std::vector<engine::Sample> samples;
};

/// The block's data (zlib stream). Throws std::runtime_error naming the column when a value
/// cannot be represented in its unit (beyond +-2^53 units: an absurd position or force);
/// such a session is left in format 1.
std::string encode_block(const BlockTicks& block);

/// Appends the `count` decoded samples of a block to `out` and their ticks to `ticks`.
/// Throws std::runtime_error with the reason (bad zlib stream, a column layout that does not
/// add up to `count` ticks). Values are not range-checked here: the reader does that.
void decode_block(const void* data, std::size_t size, std::int64_t count, std::vector<std::int64_t>& ticks,
                  std::vector<engine::Sample>& out);

}  // namespace palpa::session::detail
