#pragma once

// What the fuzz targets share: the input as bytes, and a scratch folder for the readers that take
// a path (map YAML and images are opened by name, as the programs open them).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace fleetmap::fuzz {

inline std::string_view AsText(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A folder of this process's own under $TMPDIR (or /tmp), made on first use and kept for the
// process's life: libFuzzer runs one input after another in one process, so each input rewrites
// the same few files there.
std::filesystem::path ScratchFolder();

// Writes `bytes` to `path` whole, replacing what was there; a failure is a broken set-up (abort).
void WriteScratchFile(const std::filesystem::path& path, std::string_view bytes);

}  // namespace fleetmap::fuzz
