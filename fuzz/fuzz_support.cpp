#include "fuzz/fuzz_support.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "common/core/check.hpp"

namespace fleetmap::fuzz {

namespace {

// Never destroyed, so that the exit handler below may still read it.
const std::filesystem::path* scratch_folder = nullptr;

// libFuzzer ends a timed run with exit(): the folder goes with the process, not left in /tmp
// once per run.
void RemoveScratchFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(*scratch_folder, ignored);
}

}  // namespace

std::filesystem::path ScratchFolder() {
  if (scratch_folder == nullptr) {
    const char* tmp = std::getenv("TMPDIR");
    auto* path = new std::filesystem::path(
        std::filesystem::path(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") /
        ("fleetmap-fuzz-" + std::to_string(::getpid())));
    std::error_code error;
    std::filesystem::create_directories(*path, error);
    FLEETMAP_CHECK(!error, "cannot make the fuzz scratch folder");
    scratch_folder = path;
    std::atexit(RemoveScratchFolder);
  }
  return *scratch_folder;
}

void WriteScratchFile(const std::filesystem::path& path, std::string_view bytes) {
  // A temp cleaner (or a person) may have removed the folder during a long run: that is not a
  // finding of the reader under test.
  std::error_code ignored;
  std::filesystem::create_directories(path.parent_path(), ignored);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  FLEETMAP_CHECK(out.good(), "cannot write a fuzz scratch file");
}

}  // namespace fleetmap::fuzz
