#pragma once

// Output files that appear whole or not at all.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap {

// Replaces the file at `path` with `contents`, so that a process killed mid-write leaves either
// the old file or the new one, never half of it. The bytes go into a new file beside `path`
// (`<path>.tmp.<pid>.<n>`), which is then renamed over `path`; on any failure the temporary file
// is removed and nothing at `path` changes. The new file's mode is 0666 minus the umask.
//
// A `path` that exists and is neither a regular file nor a directory (/dev/stdout, /dev/null, a
// FIFO, a symbolic link) is opened and written in place, without that guarantee: renaming over
// /dev/stdout would replace the device node itself when running as root.
//
// Errors: kUnavailable, "<path>: cannot write: <reason>", e.g.
// "out/x.vmap: cannot write: No such file or directory".
// Thread-safe: concurrent calls use distinct temporary files (concurrent writers of one `path`:
// the last rename wins).
Status WriteFileAtomically(const std::string& path, std::string_view contents);

// The same for encoded bytes (PNG, ...).
Status WriteFileAtomically(const std::string& path, const std::vector<uint8_t>& contents);

}  // namespace fleetmap
