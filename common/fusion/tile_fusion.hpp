#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/fusion/grid_window.hpp"
#include "common/fusion/newest_evidence.hpp"
#include "common/fusion/robot_trust.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/vector_map/vector_map.hpp"
#include "common/vector_map/vectorizer.hpp"

namespace fleetmap::fusion {

// A fused tile that changed: its new revision and geometry (fleet frame, on the tile lattice).
struct FusedTile {
  TileId tile;
  uint32_t revision = 0;
  vector_map::VectorMap map;
  // The newest robot tile stamp this revision reflects: a receiver's clock minus it is the
  // update's latency from the robot that caused it.
  Timestamp source_stamp;
};

// One robot's evidence for one tile, exactly as the fusion keeps it: what a store needs to rebuild
// the fused map after a restart (TileFusion::ExportContribution / ImportContribution).
struct ContributionEvidence {
  std::vector<int8_t> cells;         // 3-state, row-major, CellsPerTile() cells per side
  std::vector<uint32_t> changed_at;  // per cell: when it last changed state (deciseconds)
  Timestamp stamp;                   // the newest revision of the robot's tile seen so far
};

// The fleet's fused map, tile by tile. Each robot's tile is rasterized onto the tile's fused cells;
// a fused cell takes the state of the robot whose evidence for it is newest, where a robot's
// evidence for a cell dates from the revision in which that cell last changed state. Ties go to
// occupied. A robot that left keeps its contribution (marked stale by the server, not here).
// Changed tiles, and neighbours whose border context changed, are re-vectorized by FuseChanged().
// A robot whose map contradicts what the other robots established is quarantined: its
// contributions are kept (and exported) but not fused until it agrees again, another robot
// confirms what it saw, or an operator admits it (QuarantineOptions, RobotTrust).
//
// Not thread-safe: one fusion worker owns it.
class TileFusion {
 public:
  static StatusOr<TileFusion> Create(const FusionOptions& options);

  // A robot's new revision of a tile (fleet frame). Fails for a tile beyond max_coordinate.
  Status UpdateRobotTile(const RobotId& robot, const TileId& tile, const vector_map::VectorMap& map,
                         Timestamp stamp);
  void RemoveRobotTile(const RobotId& robot, const TileId& tile);

  // A robot's contribution to a tile, if it has one: its cells with their evidence dates.
  std::optional<ContributionEvidence> ExportContribution(const RobotId& robot,
                                                         const TileId& tile) const;
  // Replaces a robot's contribution to a tile with one exported before (by this or an earlier
  // process with the same options), as if its revisions had been fused again one by one.
  // kInvalidArgument, changing nothing, when the tile is beyond max_coordinate, the sizes do not
  // fit the tile or a cell is not free, occupied or unknown.
  Status ImportContribution(const RobotId& robot, const TileId& tile,
                            ContributionEvidence evidence);

  // Makes each tile's fused revisions continue after `revisions` (per tile, the newest revision
  // published before, e.g. by the process whose store this fusion was restored from): the tile's
  // next revision is higher, so a reader keeping the highest revision takes the new ones. Call
  // before the first FuseChanged(); tiles already fused keep their numbers.
  void ContinueRevisionsFrom(const std::map<TileId, uint32_t>& revisions);

  // Fuses and vectorizes every tile marked since the last call; returns those whose vector map
  // changed. Robots whose tiles changed are weighed against the fleet first, so a tile that
  // puts its robot in quarantine is never fused.
  StatusOr<std::vector<FusedTile>> FuseChanged();

  // Which participant speaks for `robot`: robots of one participant never confirm each other's
  // changes. Unset, a robot is its own source.
  void SetRobotSource(const RobotId& robot, std::string source);
  // An operator's word: the robot is fused from the next FuseChanged() on and never quarantined
  // again. False when it already was admitted.
  bool AdmitRobot(const RobotId& robot);
  // The robot's standing, why, and what it contradicts.
  TrustReport TrustOf(const RobotId& robot) const { return trust_.Report(robot); }
  // Robots whose standing changed in the FuseChanged() calls since the last call, and
  // quarantined robots whose figures moved (TrustReport::standing_changed false).
  std::vector<TrustReport> TakeTrustChanges();

  // The fused cells as one fleet-frame grid (yaw 0): the smallest that holds every tile when it
  // has at most options().max_grid_cells cells, else the window ChooseGridWindow() picks (the
  // largest group of nearby tiles). `shown`, if given, says which tiles it holds and how many
  // it leaves out. With `without`, the cells as if that robot had contributed nothing (what the
  // rest of the fleet says, to check the robot's placement against).
  grid::OccupancyGrid FusedGrid(GridWindow* shown = nullptr,
                                const RobotId* without = nullptr) const;
  // The fused vector map of one tile, if any.
  const FusedTile* FindFusedTile(const TileId& tile) const;
  const std::map<TileId, FusedTile>& fused_tiles() const { return vector_tiles_; }
  size_t contribution_count() const;
  // The memory held for tiles that several trusted robots share (their NewestEvidence), which
  // no one robot's tiles account for: the memory budget adds it to what the robots hold.
  uint64_t SharedEvidenceBytes() const;
  // Every (robot, tile) with a contribution.
  std::vector<std::pair<RobotId, TileId>> contributions() const;
  const FusionOptions& options() const { return options_; }

 private:
  // One robot's view of one tile.
  struct Contribution {
    grid::OccupancyGrid cells;         // 3-state, on the tile's fused cells
    std::vector<uint32_t> changed_at;  // per cell: when it last changed state (deciseconds)
    Timestamp stamp;                   // the newest revision received
    // The cells from the first known one to past the last (row-major): a robot that has seen
    // part of a tile is weighed over that part only (fusing is most of the server's time).
    size_t known_begin = 0;
    size_t known_end = 0;
    int slot = 0;  // its place in the tile's NewestEvidence, unique on the tile

    // Sets `cells` and the known span.
    void SetCells(grid::OccupancyGrid known);
    DatedCells Dated() const;
  };
  struct TileState {
    std::map<RobotId, Contribution> robots;
    grid::OccupancyGrid fused;  // 3-state
    // The trusted contributions' newest evidence, kept as they change (UpdateRobotTile); built
    // again when `newest_stale` (a standing changed, a contribution left or was imported). Only
    // where two or more trusted robots contribute: it takes 11 bytes a cell, and a tile of one
    // robot (most tiles of a sparse fleet) is fused by a copy.
    std::optional<NewestEvidence> newest;
    bool newest_stale = true;
    Timestamp newest_input;   // the latest robot tile stamp received for this tile
    uint64_t first_seen = 0;  // tiles_created_ when it appeared: the fleet's oldest area first
  };

  explicit TileFusion(const FusionOptions& options);

  grid::OccupancyGrid EmptyTileGrid(const TileId& tile) const;
  // The tile's state, created (all unknown) when it is new.
  TileState& StateOf(const TileId& tile);
  // The robot's contribution to the tile, created (empty, with a free slot) when it is new.
  static Contribution& ContributionOf(TileState& state, const RobotId& robot);
  // The trusted contributions, as NewestEvidence reads them.
  std::vector<DatedCells> TrustedCells(const TileState& state) const;
  // The tile's newest trusted evidence, built again first if stale; nullptr (and none kept)
  // while fewer than two trusted robots contribute.
  const NewestEvidence* FreshEvidence(const TileId& tile, TileState& state) const;
  uint32_t Deciseconds(Timestamp stamp) const;
  // Which trusted contributions FuseCells() takes (all of them by default).
  struct Evidence {
    const RobotId* without = nullptr;                // leaves this robot out
    const std::string* walls_only_source = nullptr;  // its robots add their occupied cells only
    const std::string* skip_source = nullptr;        // its robots add nothing
    bool corroborated_only = false;                  // robots RobotTrust says are corroborated
    bool with_quarantined = false;                   // quarantined robots' cells too
  };
  // A tile's fused cells from the trusted contributions `evidence` takes; `dates`, if given,
  // receives each cell's evidence date (0: unknown).
  grid::OccupancyGrid FuseCells(const TileId& tile, const TileState& state,
                                const Evidence& evidence,
                                std::vector<uint32_t>* dates = nullptr) const;
  bool Fused(const RobotId& robot) const { return !trust_.quarantined(robot); }
  const std::string& SourceOf(const RobotId& robot) const;
  // What every review of a tile in one pass shares: the trusted robots' cells (the tile's
  // NewestEvidence, unchanged during the pass, or fused here when it has none), and per cell the
  // newest dates quarantined robots saw it free, from two different participants.
  struct TileReview {
    const NewestEvidence* evidence = nullptr;
    grid::OccupancyGrid alone;  // the trusted cells where `evidence` is nullptr
    std::vector<uint32_t> alone_dates;
    const grid::OccupancyGrid& trusted() const {
      return evidence != nullptr ? evidence->cells() : alone;
    }
    const std::vector<uint32_t>& trusted_dates() const {
      return evidence != nullptr ? evidence->dates() : alone_dates;
    }
    std::vector<uint32_t> free_first;  // empty: no quarantined robot on the tile
    std::vector<uint32_t> free_second;
    std::vector<const std::string*> free_first_source;
  };
  TileReview MakeTileReview(const TileId& tile, TileState& state) const;
  // Whether `robot` is weighed against every other trusted contribution of the tile, whole: no
  // robot of its participant there (they add walls only) and, if it is corroborated, no trusted
  // robot that is not. Then its "others" are the tile's newest evidence without it.
  bool TakesWholeTrusted(const TileState& state, const RobotId& robot) const;
  // Counts `robot`'s contradiction of the rest of the fleet on `tile` (it contributes there).
  TileContradiction CountOn(const TileId& tile, const TileState& state, const RobotId& robot,
                            const TileReview& review) const;
  // Weighs the robots queued in to_review_ and applies what RobotTrust decides: a robot whose
  // standing changed has all its tiles fused again (and the quarantined robots there weighed
  // again: a robot released may confirm another's change).
  void ReviewTrust();
  void StandingChanged(const RobotId& robot);
  void CorroborationChanged(const RobotId& robot);
  // Recomputes a tile's fused cells; returns true if any changed, and marks neighbours whose
  // border margin changed.
  bool FuseAgain(const TileId& tile, TileState* state);
  StatusOr<vector_map::VectorMap> VectorizeWithContext(const TileId& tile) const;

  FusionOptions options_;
  vector_map::Vectorizer vectorizer_;
  Timestamp epoch_;
  std::map<TileId, TileState> tiles_;
  uint64_t tiles_created_ = 0;
  std::set<TileId> to_fuse_again_;  // robot input changed
  // Fused cells (or a neighbour's border) changed, with the newest robot stamp that caused it.
  std::map<TileId, Timestamp> to_vectorize_;
  std::map<TileId, FusedTile> vector_tiles_;
  RobotTrust trust_;
  std::map<RobotId, std::string> sources_;
  std::set<std::pair<TileId, RobotId>> to_review_;  // contributions to weigh again
  std::set<RobotId> to_decide_;                     // robots whose counts changed otherwise
  std::set<RobotId> trust_changed_;                 // since TakeTrustChanges()
  std::set<RobotId> figures_moved_;                 // likewise, standing unchanged
  // Per tile, the revision its first fused revision follows (ContinueRevisionsFrom).
  std::map<TileId, uint32_t> revisions_before_;
};

}  // namespace fleetmap::fusion
