// A counting global operator new for the no-allocation tests. Include it in exactly one
// translation unit of a test executable: replacing operator new affects the whole executable, so
// the replacement only counts, then calls malloc.
//
// Eigen allocates through malloc, not operator new; the tests pair this with Eigen's own guard
// (EIGEN_RUNTIME_NO_MALLOC, defined for every project target, and
// Eigen::internal::set_is_malloc_allowed(false)), which aborts on an Eigen heap allocation when
// assertions are on.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace flexstress::testing {
inline std::atomic<long long> g_allocations{0};
inline long long allocations() {
  return g_allocations.load(std::memory_order_relaxed);
}
}  // namespace flexstress::testing

// GCC >= 11 inlines these replacements into std::allocator and then flags free() on memory from
// operator new (-Wmismatched-new-delete), although both are ours and match.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 11
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  flexstress::testing::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  std::abort();  // the tests do not rely on bad_alloc
}
void* operator new[](std::size_t size) {
  flexstress::testing::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  std::abort();
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
