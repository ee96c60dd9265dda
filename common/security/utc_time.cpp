#include "common/security/utc_time.hpp"

namespace fleetmap::security {

std::string FormatUtc(std::time_t time, const char* format) {
  std::tm tm{};
  gmtime_r(&time, &tm);
  char text[64];
  const size_t length = std::strftime(text, sizeof(text), format, &tm);
  return std::string(text, length);
}

}  // namespace fleetmap::security
