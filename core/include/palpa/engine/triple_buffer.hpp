#pragma once
// A triple buffer: one writer publishes whole values, one reader always gets the newest
// complete one. Neither side ever waits for the other: no lock, no allocation after
// construction, no system call. The haptic thread publishes snapshots through it (scene
// state for the GUI, LoopStats) that the other thread picks up at its own pace.

#include <array>
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace palpa::engine {

/// Three slots: the writer's back slot, the reader's front slot and a middle slot with a
/// "fresh" flag, exchanged atomically.
///
/// Memory ordering. The middle slot's index and the fresh flag live in one atomic word and
/// both sides change it only by exchange (acq_rel).
/// - Writer to reader: the writer's stores into its back slot are sequenced before the
///   release half of publish()'s exchange; the reader's exchange in update() reads that
///   value (or a later one in the word's modification order, all written by
///   read-modify-writes, which continue the release sequence), so its acquire half
///   synchronizes with it and every store into the slot it takes happens before its reads.
/// - Reader to writer: the reader's loads from its old front slot are sequenced before the
///   release half of update()'s exchange, which puts that slot in the middle; the writer
///   gets it back only through a later exchange in publish(), whose acquire half makes
///   those loads happen before the writer's next stores into it.
/// At every instant the three indices (back, middle, front) are a permutation of {0, 1, 2},
/// so the two sides never touch the same slot: no data race.
template <typename T>
class TripleBuffer {
  static_assert(std::is_copy_constructible_v<T>, "TripleBuffer: T must be copy constructible");
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free, "TripleBuffer needs lock-free 32-bit atomics");

 public:
  /// All three slots start as copies of `initial` (the one place that may allocate: a T
  /// holding vectors gets its storage here, once per slot). The reader sees `initial`
  /// until the first publish.
  explicit TripleBuffer(const T& initial = T{}) : slots_{{Slot{initial}, Slot{initial}, Slot{initial}}} {}
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Writer: the slot to fill. It holds an older value, not the last one published, so
  /// write every field (or assign a whole value); writing into existing storage (same
  /// vector sizes) allocates nothing.
  T& write_slot() noexcept { return slots_[back_].value; }

  /// Writer: makes the write slot the newest value and takes a new write slot.
  void publish() noexcept {
    const std::uint32_t old_middle = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel);
    back_ = old_middle & kIndexMask;
  }

  /// Reader: takes the newest published value if there is one not yet taken; true if
  /// read() changed.
  bool update() noexcept {
    // Only the reader clears the flag, so once seen set it stays set until our exchange;
    // the relaxed look is just a shortcut and orders nothing.
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint32_t old_middle = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old_middle & kIndexMask;
    return true;
  }

  /// Reader: the value taken by the last successful update() (or the initial value).
  const T& read() const noexcept { return slots_[front_].value; }

 private:
  static constexpr std::uint32_t kIndexMask = 3;
  static constexpr std::uint32_t kFresh = 4;

  // Each slot, the shared word and each side's own index on cache lines of their own.
  struct alignas(64) Slot {
    T value;
  };
  std::array<Slot, 3> slots_;
  alignas(64) std::atomic<std::uint32_t> middle_{1};  // middle slot index | kFresh
  alignas(64) std::uint32_t back_ = 0;                // writer only
  alignas(64) std::uint32_t front_ = 2;               // reader only
};

}  // namespace palpa::engine
