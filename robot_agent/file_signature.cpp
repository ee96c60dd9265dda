#include "robot_agent/file_signature.hpp"

#include <sys/stat.h>

namespace fleetmap::agent {
namespace {

int64_t Nanoseconds(const timespec& time) {
  return static_cast<int64_t>(time.tv_sec) * 1'000'000'000 + time.tv_nsec;
}

}  // namespace

FileSignature FileSignature::Of(const std::string& path) {
  struct stat info {};
  if (path.empty() || ::stat(path.c_str(), &info) != 0) return FileSignature{};
  return FileSignature{.exists = true,
                       .device = info.st_dev,
                       .inode = info.st_ino,
                       .size = static_cast<int64_t>(info.st_size),
                       .mtime_ns = Nanoseconds(info.st_mtim),
                       .ctime_ns = Nanoseconds(info.st_ctim)};
}

}  // namespace fleetmap::agent
