#include "common/core/check.hpp"

#include <cstdio>
#include <cstdlib>

namespace fleetmap::internal {

void CheckFailed(const char* condition, const char* file, int line, std::string_view message) {
  if (message.empty()) {
    std::fprintf(stderr, "%s:%d: check failed: %s\n", file, line, condition);
  } else {
    std::fprintf(stderr, "%s:%d: check failed: %s: %.*s\n", file, line, condition,
                 static_cast<int>(message.size()), message.data());
  }
  std::fflush(stderr);
  std::abort();
}

}  // namespace fleetmap::internal
