#pragma once

// FLEETMAP_CHECK: a broken invariant is a bug, and it stops the program in Release builds too
// (unlike assert(), which NDEBUG compiles out). Expected failures (a bad file, a bad sample) are
// not invariants: they return a Status (status.hpp).
//
//   FLEETMAP_CHECK(sigma > 0.0);
//   FLEETMAP_CHECK(open_, "SqliteTransaction::Commit without Begin");
//
// On failure it prints "<file>:<line>: check failed: <condition>[: <message>]" to stderr and
// aborts, so a core dump or the test's death matcher sees the place.

#include <string_view>

namespace fleetmap::internal {

[[noreturn]] void CheckFailed(const char* condition, const char* file, int line,
                              std::string_view message = {});

}  // namespace fleetmap::internal

#define FLEETMAP_CHECK(condition, ...)                                        \
  do {                                                                        \
    if (!(condition)) [[unlikely]] {                                          \
      ::fleetmap::internal::CheckFailed(#condition, __FILE__,                 \
                                        __LINE__ __VA_OPT__(, ) __VA_ARGS__); \
    }                                                                         \
  } while (false)
