#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/status.hpp"
#include "common/fusion/tile_fusion.hpp"
#include "common/store/map_store.hpp"

namespace fleetmap::server {

// Keeps the map store in step with the fusion, and rebuilds the fusion from it at start.
//
// The fusion worker queues what changed: tile revisions (the store's latest rows and history),
// which robot contributions changed or went, and robot records. Flush() writes all of it in one
// transaction; a changed contribution's evidence (its cells and per-cell dates) is read from the
// fusion at that moment, and a contribution the fusion no longer has is deleted from the store
// with its tile rows. A failed write is kept and retried at a later Flush, at most once per
// `retry_period`; while the store is behind, revisions of one (owner, tile) replace each other
// (the newest is kept: the history misses those between), so what waits is bounded by the number
// of tiles and robots, however long the store stays unwritable.
//
// Not thread-safe: create and call from the fusion worker's thread.
class StoreSync {
 public:
  struct Options {
    std::chrono::milliseconds retry_period{1000};
  };
  // What Restore() rebuilt.
  struct Restored {
    size_t from_evidence = 0;  // contributions read back exactly
    size_t from_history = 0;   // tiles of an older store, their revisions fused again in order
    // Rows that could not be used, each with its reason. Among them, tile payloads that do not
    // decode or describe another key: the first kMaxNamedCorrupt of each table by name (owner,
    // tile, revision), then one line with how many more.
    std::vector<std::string> skipped;
    size_t tile_rows_checked = 0;  // tile_latest and tile_history rows decoded
    size_t corrupt_rows = 0;       // among them, every corrupt one
    // The latest tiles of robots placed by registration, in their own map frames (owners
    // store::MapFrameOwner): not fused here; the fusion worker places them again.
    std::vector<store::TileRecord> map_frame_tiles;
  };
  // Corrupt rows named one by one per table; past this, counted in one line.
  static constexpr size_t kMaxNamedCorrupt = 20;
  enum class FlushResult {
    kIdle,     // nothing to write
    kWritten,  // everything queued is in the store
    kFailed,   // the write failed; everything stays queued
    kWaiting,  // behind, and the next attempt is not due yet
  };

  // `store` must outlive this; null keeps nothing.
  explicit StoreSync(store::MapStore* store, Options options);

  // Rebuilds `fusion` (empty) from the store: each robot contribution from its stored evidence;
  // a robot tile with no evidence (a store written before schema version 3) by fusing its stored
  // revisions again, oldest first, and queueing its evidence for the next Flush. Rows whose key
  // disagrees with their payload, or that do not decode, are skipped with a reason. Every tile
  // payload (each latest row and the whole history) is decoded once, so that a corrupt one is
  // named at start-up even where the restore does not need it. The fused tiles' revisions go on
  // from the stored ones (TileFusion::ContinueRevisionsFrom). Fails only when the store cannot be
  // read.
  StatusOr<Restored> Restore(fusion::TileFusion* fusion);

  // A tile revision to store (robot or fused).
  // Each of these refuses a record the store would refuse (kInvalidArgument), so that one bad
  // record cannot hold back every later write.
  Status AddTile(store::TileRecord record);
  // A robot's contribution to `tile` changed or was removed from the fusion.
  Status ContributionChanged(const RobotId& robot, const TileId& tile);
  Status AddRobot(store::RobotRecord robot);

  // Writes what is queued, unless the store is behind and `now` is before the next attempt.
  FlushResult Flush(const fusion::TileFusion& fusion, std::chrono::steady_clock::time_point now);

  // The last write failed and records wait for the next attempt.
  bool behind() const { return behind_; }
  // Records waiting: tile revisions, changed contributions and robots.
  size_t pending() const { return tiles_.size() + changed_.size() + robots_.size(); }
  // Failed writes since the last successful one.
  uint64_t failed_attempts() const { return failed_attempts_; }
  const Status& last_error() const { return last_error_; }

 private:
  // Keeps only the newest revision of each (owner, tile) in tiles_, and indexes them.
  void Coalesce();
  StatusOr<store::StoreBatch> MakeBatch(const fusion::TileFusion& fusion) const;
  // Decodes every history and latest tile payload; names the corrupt ones in `restored` and
  // returns their rows' keys, so that the restore skips them without naming them twice.
  // One stored row: owner, tile, revision and stamp.
  using RowKey = std::tuple<store::TileOwner, TileId, uint32_t, int64_t>;
  StatusOr<std::set<RowKey>> CheckTilePayloads(const std::vector<store::TileRecord>& latest,
                                               Restored* restored) const;

  store::MapStore* store_;
  Options options_;
  std::vector<store::TileRecord> tiles_;
  std::map<store::TileKey, size_t> tile_index_;   // into tiles_, while behind_
  std::set<std::pair<RobotId, TileId>> changed_;  // contributions changed or removed
  std::map<RobotId, store::RobotRecord> robots_;
  bool behind_ = false;
  uint64_t failed_attempts_ = 0;
  Status last_error_;
  std::chrono::steady_clock::time_point next_attempt_{};
};

}  // namespace fleetmap::server
