#pragma once

// Times as the security folder's documents and messages print them: UTC, strftime formats.

#include <ctime>
#include <string>

namespace fleetmap::security {

// `time` in UTC with a strftime `format`, e.g. "%Y-%m-%dT%H:%M:%S".
std::string FormatUtc(std::time_t time, const char* format);

}  // namespace fleetmap::security
