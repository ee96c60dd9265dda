#pragma once

// What every program prints for `--version` (added by ParseCommandLine, command_line.hpp): the
// fleetmap version (CMake's project(VERSION)), the git commit it was built from, and the Fast DDS
// it was compiled against, so that a bug report names all three.

#include <string>
#include <string_view>

namespace fleetmap::config {

// "0.1.0".
std::string_view FleetmapVersion();
// The commit of the build's source tree, 12 hex digits, with "-dirty" when tracked files had
// changed; "unknown" when the sources were not a git checkout (a release tarball).
std::string_view GitCommit();
// The Fast DDS (fastrtps) version of the headers the build used: "2.9.1".
std::string_view FastDdsVersion();

// Two lines: "<program> <version> (commit <commit>)" and "Fast DDS <version>".
std::string VersionText(std::string_view program);

}  // namespace fleetmap::config
