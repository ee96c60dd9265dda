#pragma once

// The include directions of docs/architecture.md, read from the document itself and checked
// against a source tree, so the picture a newcomer reads is the rule the build keeps.
//
// A module is a folder: `common/<name>`, `bench/<name>` and `cli/<name>` (two levels; files right
// in `bench/` or `cli/` belong to the top-level module), or a top-level folder (`server`,
// `robot_agent`). The rules block lists, per module, the modules its files may
// include; `idl` stands for the generated DDS headers (`<package>/msg/...`). Files under `tests/`
// may include any module, but, like every module other than the owner, not another module's
// `internal/` headers nor generated ones, unless the block names them as exceptions.

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::architecture {

struct IncludeRules {
  // module -> the modules it may include (its own is always allowed).
  std::map<std::string, std::set<std::string>> may_include;
  // Files or folders (relative paths; a folder ends in '/') allowed to include another
  // module's internal/ headers and the generated ones: tests that play a wire peer.
  std::vector<std::string> edge_exceptions;
};

struct IncludeViolation {
  std::string file;  // relative to the root
  int line = 0;
  std::string include;
  std::string why;
};

// Reads the ```include-rules block of a Markdown document. Lines:
//   <module> -> <module> <module> ...
//   edge-exception <path> <path> ...
// '#' starts a comment. Fails naming the file and line of anything else.
StatusOr<IncludeRules> ReadIncludeRules(const std::filesystem::path& markdown);

// Every #include "..." under `root` (.hpp/.cpp/.h/.cxx in the rules' modules and in tests/) that
// breaks the rules, and every source folder the rules do not name.
std::vector<IncludeViolation> CheckIncludes(const std::filesystem::path& root,
                                            const IncludeRules& rules);

}  // namespace fleetmap::architecture
