#pragma once

// The byte baselines the vector tiles are compared with (issue 17): what the same map changes
// cost on each ROS-native grid wire, as the agents measured them (WireBaselines), named, and the
// headline ratio against the smallest of them.

#include <cstdint>
#include <string>
#include <vector>

#include "common/core/robot_status.hpp"

namespace fleetmap::bench {

struct BaselineBytes {
  std::string name;  // what was counted, e.g. "OccupancyGridUpdate patches, zstd -3"
  std::string key;   // for JSON and CSV, e.g. "patches_zstd3"
  uint64_t bytes = 0;
};

// The five baselines, in the order the tables print them: whole grids, patches raw, zstd -3,
// zstd -19, LZ4.
std::vector<BaselineBytes> Baselines(const WireBaselines& measured);

// The smallest baseline (the fair comparison).
BaselineBytes SmallestBaseline(const WireBaselines& measured);

// "N.Nx fewer bytes than the smallest baseline, <name> (B bytes)" ("more" when the tiles are the
// larger), or why there is no ratio (no tile bytes, nothing measured, accounting unfinished).
std::string HeadlineRatio(uint64_t tile_bytes, const WireBaselines& measured);

// "B (N.Nx)": a baseline's bytes and how many times the tiles' bytes they are.
std::string BytesAndRatio(uint64_t baseline_bytes, uint64_t tile_bytes);

}  // namespace fleetmap::bench
