#pragma once
// A bounded single-producer single-consumer queue for the haptic thread: commands from the
// GUI, samples to the session writer. Wait-free on both sides: no allocation, no lock, no
// system call; a full queue refuses the value and the producer counts the drop.

#include <array>
#include <atomic>
#include <cstddef>
#include <type_traits>

namespace palpa::engine {

/// Exactly one thread may call try_push and exactly one (other) thread try_pop; either
/// may call size_approx. Capacity must be a power of two.
template <typename T, std::size_t Capacity>
class SpscQueue {
  static_assert(Capacity > 0 && (Capacity & (Capacity - 1)) == 0, "SpscQueue: Capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "SpscQueue: T must be trivially copyable");
  static_assert(std::is_default_constructible_v<T>, "SpscQueue: T must be default constructible");
  static_assert(std::atomic<std::size_t>::is_always_lock_free, "SpscQueue needs lock-free std::size_t atomics");

 public:
  SpscQueue() = default;
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  static constexpr std::size_t capacity() { return Capacity; }

  /// Producer: false (and nothing stored) when the queue is full.
  bool try_push(const T& value) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);  // only we write it
    if (tail - head_seen_ == Capacity) {
      // Looks full from our last look at head: look again (acquire: the consumer has
      // finished reading every slot it released).
      head_seen_ = head_.load(std::memory_order_acquire);
      if (tail - head_seen_ == Capacity) return false;
    }
    slots_[tail & kMask] = value;
    tail_.store(tail + 1, std::memory_order_release);  // publishes the slot
    return true;
  }

  /// Consumer: false (and `out` untouched) when the queue is empty.
  bool try_pop(T& out) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);  // only we write it
    if (head == tail_seen_) {
      tail_seen_ = tail_.load(std::memory_order_acquire);  // the slot's contents come with it
      if (head == tail_seen_) return false;
    }
    out = slots_[head & kMask];
    head_.store(head + 1, std::memory_order_release);  // hands the slot back
    return true;
  }

  /// The number of values in the queue at some instant during the call; exact when
  /// neither side is running.
  std::size_t size_approx() const noexcept {
    // Head first: tail only grows, so the difference cannot wrap below zero.
    const std::size_t head = head_.load(std::memory_order_acquire);
    const std::size_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t n = tail - head;
    return n < Capacity ? n : Capacity;
  }

 private:
  static constexpr std::size_t kMask = Capacity - 1;

  // Indices grow monotonically (2^64 pushes never wrap in practice, and when they do the
  // unsigned differences stay right because Capacity divides 2^64) and are masked on
  // access. Each side's index and its cached copy of the other side's index share a cache
  // line (64 bytes on x86-64 and common ARM cores) of their own, away from the slots.
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to write (producer)
  std::size_t head_seen_ = 0;                      // producer's last look at head_
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to read (consumer)
  std::size_t tail_seen_ = 0;                      // consumer's last look at tail_
  alignas(64) std::array<T, Capacity> slots_{};
};

}  // namespace palpa::engine
