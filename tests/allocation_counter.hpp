#pragma once
// Counting heap allocations in a test executable, to prove a steady state allocates nothing.
// Include this header in exactly ONE source file of a test executable: it replaces the global
// operator new/delete of that whole executable (so keep such tests in executables of their own).
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace rtmot::test {

// Test instrumentation: process-wide counters are the point here, and only this executable has
// them.
struct AllocationCounters {
  std::atomic<bool> counting{false};
  std::atomic<long> allocations{0};
  std::atomic<std::size_t> largest{0};
  // Threads whose first allocation ever fell inside the scope: a pool thread's first task sets up
  // its per-thread state (OpenCV's RNG and TLS slots: 3 blocks, 328 bytes with OpenCV 4.6, kept
  // until the thread ends), once per thread, in whichever frame a scheduler first gives it work.
  std::atomic<long> new_threads{0};
};

inline AllocationCounters& allocation_counters() {
  static AllocationCounters counters;
  return counters;
}

/// Counts allocations (and the largest one) made by any thread while it is alive.
class CountingScope {
 public:
  CountingScope() {
    auto& c = allocation_counters();
    c.allocations = 0;
    c.largest = 0;
    c.new_threads = 0;
    c.counting = true;
  }
  ~CountingScope() { allocation_counters().counting = false; }
  CountingScope(const CountingScope&) = delete;
  CountingScope& operator=(const CountingScope&) = delete;

  long allocations() const { return allocation_counters().allocations.load(); }
  std::size_t largest() const { return allocation_counters().largest.load(); }
  long new_threads() const { return allocation_counters().new_threads.load(); }
};

inline void* counted_allocation(std::size_t size) {
  auto& c = allocation_counters();
  thread_local bool allocated_before = false;  // a plain bool: constant-initialized, no allocation
  const bool first_of_this_thread = !allocated_before;
  allocated_before = true;
  if (c.counting.load(std::memory_order_relaxed)) {
    if (first_of_this_thread) c.new_threads.fetch_add(1, std::memory_order_relaxed);
    c.allocations.fetch_add(1, std::memory_order_relaxed);
    std::size_t seen = c.largest.load(std::memory_order_relaxed);
    while (size > seen && !c.largest.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
    }
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

}  // namespace rtmot::test

void* operator new(std::size_t size) {
  return rtmot::test::counted_allocation(size);
}
void* operator new[](std::size_t size) {
  return rtmot::test::counted_allocation(size);
}
// The nothrow forms too (std::stable_sort's temporary buffer uses them): left to the runtime's
// own, their memory would reach the free() below, a mismatch AddressSanitizer reports.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return rtmot::test::counted_allocation(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return rtmot::test::counted_allocation(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
