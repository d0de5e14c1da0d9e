// Overridable assertion for programming errors (not for bad input: that gets an Error).
//
// Define FLEXSTRESS_ASSERT(condition, message) before including any flexstress header to route
// assertion failures into your own handler (a game engine's crash reporter, a test framework).
// By default assertions are active unless NDEBUG or FLEXSTRESS_NO_ASSERT is defined; a failed
// assertion prints the condition, the message and the location, then aborts.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace flexstress::detail {

[[noreturn]] inline void assertion_failed(const char* condition, const char* message,
                                          const char* file, int line) {
  std::fprintf(stderr, "flexstress: assertion failed: %s\n  %s\n  at %s:%d\n", condition, message,
               file, line);
  std::abort();
}

}  // namespace flexstress::detail

#ifndef FLEXSTRESS_ASSERT
#if defined(NDEBUG) || defined(FLEXSTRESS_NO_ASSERT)
#define FLEXSTRESS_ASSERT(condition, message) static_cast<void>(0)
#else
#define FLEXSTRESS_ASSERT(condition, message) \
  ((condition) ? static_cast<void>(0)         \
               : ::flexstress::detail::assertion_failed(#condition, message, __FILE__, __LINE__))
#endif
#endif
