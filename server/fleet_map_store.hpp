#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/store/map_store.hpp"
#include "common/transport/state_messages.hpp"
#include "common/transport/vector_tile_message.hpp"
#include "server/store_sync.hpp"

namespace fleetmap::server {

// Where the fleet map is kept across restarts: an SQLite map store (WAL) that holds every robot
// tile and fused tile revision, each robot contribution's evidence, the robots, the operators'
// admissions and the finished mapping sessions. It restores a FleetMap at start and keeps what
// each round changed; writes are batched (one transaction a round) and retried while the store
// is behind, and what went wrong is logged and counted. Not thread-safe: the fusion worker's.
class FleetMapStore {
 public:
  struct Options {
    std::string path;
    // Tile revisions the history keeps, oldest dropped first (0: all).
    int64_t history_rows = 2'000'000;
    // A store another server holds is waited for this long, then refused.
    std::chrono::milliseconds lock_timeout{std::chrono::seconds(10)};
  };

  // Opens (or creates) the store; fails when another server holds it past the lock timeout.
  static StatusOr<std::unique_ptr<FleetMapStore>> Open(const Options& options);

  // Rebuilds `map` (new, empty) from the store: admissions, robot contributions, the map-frame
  // tiles of robots placed by registration. Rows that cannot be used are named in the log.
  Status Restore(fusion::FleetMap& map);

  // Queues what one round changed: robot tiles as received, changed contributions, and the
  // fused tiles `fused` as published.
  void Keep(const fusion::FleetMapChanges& changes,
            const std::vector<transport::VectorTileMessage>& fused);
  // An operator's admission, written at once (it must outlive a restart).
  void KeepAdmission(const transport::RobotAdmissionMessage& admission);
  void KeepRobot(store::RobotRecord robot);
  // Writes what is queued (one transaction). A final flush at stop ignores the retry period and
  // says what is lost.
  void Flush(const fusion::FleetMap& map, std::chrono::steady_clock::time_point now);
  void FinalFlush(const fusion::FleetMap& map);

  store::MapStore* store() { return store_.get(); }
  uint64_t errors() const { return errors_; }  // failed writes (each retried) and refused records
  bool behind() const { return sync_.behind(); }
  size_t pending() const { return sync_.pending(); }

 private:
  FleetMapStore(const Options& options, std::unique_ptr<store::MapStore> store)
      : options_(options), store_(std::move(store)), sync_(store_.get(), StoreSync::Options{}) {}

  void KeepTile(const store::TileOwner& owner, const vector_map::VectorTile& tile);
  void RestoreMapFrameTiles(fusion::FleetMap& map, const std::vector<store::TileRecord>& rows);
  void Failed(const char* what, const Status& status);

  Options options_;
  std::unique_ptr<store::MapStore> store_;
  StoreSync sync_;
  uint64_t errors_ = 0;
};

}  // namespace fleetmap::server
