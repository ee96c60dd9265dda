#pragma once

// The first bytes of PNG files written by hand, to test what is decided from a header alone.

#include <cstdint>
#include <string>

namespace fleetmap::grid::testing {

inline std::string Be32(uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16),
          static_cast<char>(value >> 8), static_cast<char>(value)};
}

// A PNG chunk; the CRC is left zero (headers are read without checking it).
inline std::string PngChunk(const std::string& type, const std::string& data) {
  return Be32(static_cast<uint32_t>(data.size())) + type + data + Be32(0);
}

// Signature and IHDR, then `more` chunks. Without pixel data decoding fails, so a size refusal on
// such a file shows that the check came before any decoding.
inline std::string PngHead(uint32_t width, uint32_t height, int depth, int color_type,
                           const std::string& more = "") {
  const std::string ihdr = Be32(width) + Be32(height) + static_cast<char>(depth) +
                           static_cast<char>(color_type) + std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + PngChunk("IHDR", ihdr) + more;
}

}  // namespace fleetmap::grid::testing
