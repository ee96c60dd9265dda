#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>

namespace fleetmap::agent {

// What a file looks like from outside, read with one stat() and no byte of content: enough to
// tell that it was rewritten, in place (size and modification time change) or by renaming another
// file over it (the inode changes). The status change time also catches a rewrite whose
// modification time was set back (cp -p, rsync -t). A missing file has a signature too (all zero),
// so a file that appears or disappears counts as a change. Times are kept to the nanosecond; a
// rewrite that keeps the size and lands within the file system's timestamp granularity of the
// previous one is the one change this cannot see.
struct FileSignature {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  int64_t size = 0;
  int64_t mtime_ns = 0;
  int64_t ctime_ns = 0;

  // The signature of `path` now (stat follows symbolic links); that of a missing file when `path`
  // is empty or cannot be stat'ed.
  static FileSignature Of(const std::string& path);

  friend bool operator==(const FileSignature&, const FileSignature&) = default;
};

}  // namespace fleetmap::agent
