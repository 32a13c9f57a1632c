#pragma once
// A counting global operator new for the real-time tests: include it in exactly one source
// file of a test binary (it defines the replacement functions), then compare
// palpa::test::allocations() before and after the code that must not allocate.
#include <atomic>
#include <cstdlib>
#include <new>

// The replacement operator new allocates with malloc, so releasing with free is right;
// GCC's -Wmismatched-new-delete cannot see that through the replacement.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace palpa::test {
inline std::atomic<long> g_allocation_count{0};
inline long allocations() { return g_allocation_count.load(std::memory_order_relaxed); }
}  // namespace palpa::test

void* operator new(std::size_t size) {
  palpa::test::g_allocation_count.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
