#include "fuzz/fuzz_support.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "common/core/check.hpp"

namespace fleetmap::fuzz {

std::filesystem::path ScratchFolder() {
  static const std::filesystem::path folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path path =
        std::filesystem::path(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") /
        ("fleetmap-fuzz-" + std::to_string(::getpid()));
    std::error_code error;
    std::filesystem::create_directories(path, error);
    FLEETMAP_CHECK(!error, "cannot make the fuzz scratch folder");
    return path;
  }();
  return folder;
}

void WriteScratchFile(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  FLEETMAP_CHECK(out.good(), "cannot write a fuzz scratch file");
}

}  // namespace fleetmap::fuzz
