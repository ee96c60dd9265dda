#pragma once

// The batches store_writer_helper commits, shared with the crash test that checks them.

#include <string>
#include <vector>

#include "common/store/store_records.hpp"

namespace fleetmap::store::testing {

inline constexpr char kWriterRobot[] = "robot_a";
inline constexpr int kWriterTilesPerBatch = 40;

// Batch `batch`: the robot's tiles (batch, 0..kWriterTilesPerBatch-1) at revision batch + 1, and
// the fused tile (0, 0) at the same revision, so every batch also updates one existing row.
inline std::vector<TileRecord> WriterBatch(int batch) {
  std::vector<TileRecord> tiles;
  const int64_t stamp_ns = 1'000'000'000 + static_cast<int64_t>(batch) * 1000;
  const auto revision = static_cast<uint32_t>(batch + 1);
  for (int i = 0; i < kWriterTilesPerBatch; ++i) {
    std::string payload = "batch " + std::to_string(batch) + " tile " + std::to_string(i) + ";";
    payload.resize(1024, static_cast<char>('a' + (batch + i) % 26));
    tiles.push_back({TileOwner::Robot(RobotId{kWriterRobot}),
                     {batch, i},
                     revision,
                     stamp_ns,
                     std::move(payload)});
  }
  tiles.push_back(
      {TileOwner::Fleet(), {0, 0}, revision, stamp_ns, "fused " + std::to_string(batch)});
  return tiles;
}

}  // namespace fleetmap::store::testing
