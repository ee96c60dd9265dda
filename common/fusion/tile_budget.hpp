#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/fusion/refusal.hpp"
#include "common/fusion/tile_cost.hpp"

namespace fleetmap::fusion {

// What robots' tiles may cost the server once decoded (docs/fleet.md, "Admission control").
// Robot ids are free to invent, DDS participants cheap to open: so every robot's tiles count
// towards its robot id, the participant that sent them (all the ids it speaks for together) and
// its host, and all robots' tiles towards one global memory budget.
struct BudgetOptions {
  // One tile, decoded: checked while the reader decodes it, before the memory is allocated.
  size_t max_vertices_per_tile = 32'768;
  size_t max_rings_per_tile = 4'096;
  // Cells one tile may paint (rasterized free polygons and obstacle bands, overlaps counted each
  // time), in tiles' worth of fused cells: an honest tile paints at most about one.
  double max_painted_tiles_per_tile = 4.0;
  // One robot id, all its tiles.
  uint64_t max_vertices_per_robot = 4'000'000;
  double max_painted_tiles_per_robot = 2'048.0;
  uint64_t max_bytes_per_robot = uint64_t{496} << 20;
  // Cells painted per second, sustained and in a burst, per participant (its ids share it): the
  // fusion work one participant may ask for. A joining robot's whole map fits in the burst.
  double max_painted_tiles_per_second = 40.0;
  double burst_painted_tiles = 2'048.0;
  // The memory all ids of one participant, and of one host, may hold: this many robots' worth.
  double robots_per_participant = 2.0;
  double robots_per_host = 4.0;
  // The memory all robots' tiles may hold together. When a tile would exceed it, the robots
  // that were claimed last give way first: their data are dropped (newest first) if that makes
  // room for an older robot's tile, and a newer robot's tile is refused.
  uint64_t max_memory_bytes = uint64_t{768} << 20;

  size_t MaxGeometryBytes() const;  // the decompressed geometry of a tile at most
  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// Charges and releases robots' tiles against BudgetOptions. Who pays is a Source: the robot id,
// the participant (writer GUID prefix) and the host it came from (empty where unknown: restored
// tiles, hosts not yet discovered). DDS-free and deterministic given the steady clock.
// Not thread-safe: the fusion worker owns it (through TileAdmission).
class TileBudget {
 public:
  struct Source {
    RobotId robot;
    std::string participant;
    std::string host;
  };
  struct Refused {
    Refusal reason;
    std::string detail;
  };
  // A tile that may be admitted, and the robots whose data must be dropped first to make room
  // (newest claimed first; empty unless the global budget was reached).
  struct Charged {
    std::vector<RobotId> evict;
  };

  TileBudget(const BudgetOptions& options, const fusion::FusionOptions& fusion);

  // The per-tile limits alone (no state).
  std::optional<Refused> CheckTile(const TileId& tile, const TileCost& cost) const;
  // Charges `cost` for `source.robot`'s `tile` (replacing what the tile cost until now) when the
  // tile, the robot, its participant, its host, the participant's painting rate and the global
  // budget allow it, or names the budget it would exceed. After a Charged with evictions, the
  // caller must release every tile of the robots named (ReleaseRobot).
  std::variant<Charged, Refused> Charge(const Source& source, const TileId& tile,
                                        const TileCost& cost,
                                        std::chrono::steady_clock::time_point now);
  // A tile that exists without passing Charge (restored from the store), at what it costs.
  void Adopt(const RobotId& robot, const TileId& tile, const TileCost& cost);
  void Release(const RobotId& robot, const TileId& tile);
  // Every tile of `robot`; it is a new robot when it comes again.
  void ReleaseRobot(const RobotId& robot);

  std::vector<TileId> TilesOf(const RobotId& robot) const;
  TileCost robot_cost(const RobotId& robot) const;
  uint64_t participant_bytes(const std::string& participant) const;
  // The memory the fusion holds for tiles several robots share, which no robot pays for alone
  // (TileFusion::SharedEvidenceBytes()): counted in the global budget, never in a robot's.
  void SetSharedBytes(uint64_t bytes) { shared_bytes_ = bytes; }
  uint64_t shared_bytes() const { return shared_bytes_; }
  // What counts against max_memory_bytes: the robots' tiles and the shared memory.
  uint64_t held_bytes() const { return total_.bytes + shared_bytes_; }

 private:
  struct Robot {
    uint64_t order = 0;  // claim order: a larger one was claimed later
    std::string participant;
    std::string host;
    std::map<TileId, TileCost> tiles;
    TileCost total;
  };
  struct Rate {
    double tokens = 0.0;
    std::chrono::steady_clock::time_point refilled{};
  };

  Robot& RobotOf(const Source& source);
  std::optional<Refused> CheckRate(const Source& source, double painted_tiles,
                                   std::chrono::steady_clock::time_point now);
  // Robots claimed after `robot`, newest first, whose release brings the global total under the
  // budget with `extra` more bytes; nullopt if even all of them would not.
  std::optional<std::vector<RobotId>> NewerToEvict(const Robot& robot, uint64_t extra) const;

  BudgetOptions options_;
  uint64_t cells_per_tile_;
  std::map<RobotId, Robot> robots_;
  std::map<std::string, uint64_t> participant_bytes_;
  std::map<std::string, uint64_t> host_bytes_;
  std::map<std::string, Rate> rates_;  // by participant
  TileCost total_;
  uint64_t shared_bytes_ = 0;
  uint64_t next_order_ = 1;
};

}  // namespace fleetmap::fusion
