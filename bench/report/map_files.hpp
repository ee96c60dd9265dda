#pragma once

// The maps a benchmark over a directory measures (`bench vectorize --maps DIR`, `bench route-graph
// --maps DIR`): every map_server YAML in it, in name order. Any thread.

#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::bench {

// kNotFound naming `dir` when it is not a directory, cannot be listed or holds no *.yaml file.
StatusOr<std::vector<std::string>> MapFilesIn(const std::string& dir);

}  // namespace fleetmap::bench
